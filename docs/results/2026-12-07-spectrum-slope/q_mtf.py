"""Physical pixel response from the 4x supersampled ideal render: pixel-area integration (box), diffraction of a
circular f/N aperture (8-14 um, weighted by 300 K Planck), the simulator's Gaussian, noise, and a camera's spatial filter."""
import sys, glob, numpy as np, cv2
sys.path.insert(0, '/tmp/slope'); from slope import *
PITCH_UM = 12.0; SS = 4
files = sorted(glob.glob('/tmp/slope/pr_ss4/radiometric/*.png'))[::5]
full = np.load('pr_full.npz'); mask = full['spread_png'] >= 2           # same frames as pr_full (0,5,...)
assert len(files) == len(mask)
def planck_w(lam_um, T=300.0):
    c1, c2 = 1.191e8, 1.4388e4
    return c1 / lam_um ** 5 / (np.exp(c2 / (lam_um * T)) - 1)
def diffraction_mtf(shape, fnum):
    h, w = shape
    f = np.hypot(np.fft.fftfreq(h)[:, None], np.fft.fftfreq(w)[None, :]) / (PITCH_UM / SS * 1e-3)   # cycles/mm
    lams = np.linspace(8, 14, 25); wts = planck_w(lams); wts /= wts.sum()
    m = np.zeros(shape)
    for lam, wt in zip(lams, wts):
        x = np.clip(f * lam * 1e-3 * fnum, 0, 1)
        m += wt * (2 / np.pi) * (np.arccos(x) - x * np.sqrt(1 - x * x))
    return m
MT = {}
def apply_mtf(t, fnum):
    if fnum not in MT: MT[fnum] = diffraction_mtf(t.shape, fnum)
    return np.real(np.fft.ifft2(np.fft.fft2(t) * MT[fnum])).astype(np.float32)
def box(t): return cv2.resize(t, (256, 192), interpolation=cv2.INTER_AREA)
def point(t): return cv2.resize(t[1::2, 1::2], (256, 192), interpolation=cv2.INTER_AREA)[::1, ::1] if False else t[2::4, 2::4] * 0.25 + t[1::4, 1::4] * 0.25 + t[1::4, 2::4] * 0.25 + t[2::4, 1::4] * 0.25
rng = np.random.default_rng(1)
fpn = (rng.standard_normal((192, 256)) * 0.05 + rng.standard_normal((1, 256)) * 0.03).astype(np.float32)
def noisy(t):
    return np.round((t + fpn + rng.standard_normal(t.shape).astype(np.float32) * 0.04) / 0.01) * 0.01
def g(t, s): return cv2.GaussianBlur(t, (0, 0), s, borderType=cv2.BORDER_REFLECT) if s > 0 else t
variants = {
    'point sample (as rendered)': lambda t: point(t),
    'point + Gaussian 0.5 (current PSF)': lambda t: g(point(t), 0.5),
    'box (pixel area, 100% fill)': lambda t: box(t),
    'box + Gaussian 0.5': lambda t: g(box(t), 0.5),
    'diffraction f/1.0 + box': lambda t: box(apply_mtf(t, 1.0)),
    'diffraction f/1.1 + box': lambda t: box(apply_mtf(t, 1.1)),
    'diffraction f/1.3 + box': lambda t: box(apply_mtf(t, 1.3)),
    'point + Gaussian 0.5 + noise (current model)': lambda t: noisy(g(point(t), 0.5)),
    'diffraction f/1.1 + box + noise': lambda t: noisy(box(apply_mtf(t, 1.1))),
    'diffraction f/1.1 + box + noise + spatial filter 0.9': lambda t: g(noisy(box(apply_mtf(t, 1.1))), 0.9),
    'point + Gaussian 0.5 + noise + spatial filter 0.9': lambda t: g(noisy(g(point(t), 0.5)), 0.9),
}
res = {k: [] for k in variants}
for i, f in enumerate(files):
    if not mask[i]: continue
    t = (cv2.imread(f, cv2.IMREAD_UNCHANGED).astype(np.float32) / 100.0 - 273.15)
    for k, fn in variants.items():
        res[k].append(realism_slope(fn(t)))
b = np.array(res['point sample (as rendered)'])
print('frames', len(b), '(views not blank in the default render)')
for k, v in res.items():
    v = np.array(v); print('%-55s median %.3f  paired vs point sample %+.3f' % (k, np.median(v), np.median(v - b)))
