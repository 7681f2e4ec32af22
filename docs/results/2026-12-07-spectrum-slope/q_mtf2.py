"""(1) Can the physical MTF be applied cheaply to the point-sampled 256x192 render (no supersampling)?
(2) Consistency: our ideal room seen through an E8xt-like chain (17 um pitch, f/1.1 diffraction, box, noise, sigma-0.9 filter)."""
import sys, glob, numpy as np, cv2
sys.path.insert(0, '/tmp/slope'); from slope import *
exec(open('/tmp/slope/q_mtf.py').read().split('variants = {')[0])
files = sorted(glob.glob('/tmp/slope/pr_ss4/radiometric/*.png'))[::5]
def mtf256(fnum, pitch_um, shape=(192, 256)):
    h, w = shape
    fy = np.fft.fftfreq(h)[:, None]; fx = np.fft.fftfreq(w)[None, :]
    f = np.hypot(fx, fy) / (pitch_um * 1e-3)
    lams = np.linspace(8, 14, 25); wts = planck_w(lams); wts /= wts.sum()
    m = np.zeros(shape)
    for lam, wt in zip(lams, wts):
        x = np.clip(f * lam * 1e-3 * fnum, 0, 1); m += wt * (2 / np.pi) * (np.arccos(x) - x * np.sqrt(1 - x * x))
    return m * np.sinc(fx) * np.sinc(fy)       # pixel-area (box) MTF, 100 % fill
M12 = mtf256(1.1, 12.0)
def filt(t, M): return np.real(np.fft.ifft2(np.fft.fft2(t) * M)).astype(np.float32)
PITCH_UM = 17.0   # E8xt-like chain on the 4x grid: diffraction for 17 um pixels
MT.clear()
res = {k: [] for k in ['point', 'point x MTF(12um,f/1.1) x box, at 256', 'supersampled diffraction(12um,f/1.1)+box',
                       'E8xt-like: 17um f/1.1 + box + noise + filter 0.9', 'E8xt-like without filter']}
for i, f in enumerate(files):
    if not mask[i]: continue
    t = (cv2.imread(f, cv2.IMREAD_UNCHANGED).astype(np.float32) / 100.0 - 273.15)
    p = point(t)
    res['point'].append(realism_slope(p))
    res['point x MTF(12um,f/1.1) x box, at 256'].append(realism_slope(filt(p, M12)))
    e = box(apply_mtf(t, 1.1))
    res['E8xt-like without filter'].append(realism_slope(noisy(e)))
    res['E8xt-like: 17um f/1.1 + box + noise + filter 0.9'].append(realism_slope(g(noisy(e), 0.9)))
PITCH_UM = 12.0; MT.clear()
for i, f in enumerate(files):
    if not mask[i]: continue
    t = (cv2.imread(f, cv2.IMREAD_UNCHANGED).astype(np.float32) / 100.0 - 273.15)
    res['supersampled diffraction(12um,f/1.1)+box'].append(realism_slope(box(apply_mtf(t, 1.1))))
b = np.array(res['point'])
for k, v in res.items():
    v = np.array(v); print('%-52s median %.3f  paired vs point %+.3f' % (k, np.median(v), np.median(v - b)))
