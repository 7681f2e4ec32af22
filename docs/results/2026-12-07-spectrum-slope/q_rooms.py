"""Expected effect, per room, of the physically derived pixel response (diffraction x pixel area, applied to T_true at 256x192,
then the sensor's noise) and of a camera spatial filter, measured by post-processing."""
import sys, numpy as np, cv2
sys.path.insert(0, '/tmp/slope'); from slope import *
exec(open('/tmp/slope/q_mtf2.py').read().split('M12 = ')[0].split('exec(')[0])
def planck_w(lam_um, T=300.0):
    return 1.191e8 / lam_um ** 5 / (np.exp(1.4388e4 / (lam_um * T)) - 1)
def mtf256(fnum, pitch_um, shape=(192, 256)):
    h, w = shape
    fy = np.fft.fftfreq(h)[:, None]; fx = np.fft.fftfreq(w)[None, :]
    f = np.hypot(fx, fy) / (pitch_um * 1e-3)
    lams = np.linspace(8, 14, 25); wts = planck_w(lams); wts /= wts.sum()
    m = np.zeros(shape)
    for lam, wt in zip(lams, wts):
        x = np.clip(f * lam * 1e-3 * fnum, 0, 1); m += wt * (2 / np.pi) * (np.arccos(x) - x * np.sqrt(1 - x * x))
    return m * np.sinc(fx) * np.sinc(fy)
def filt(t, M): return np.real(np.fft.ifft2(np.fft.fft2(t) * M)).astype(np.float32)
def g(t, s): return cv2.GaussianBlur(t, (0, 0), s, borderType=cv2.BORDER_REFLECT)
Ms = {F: mtf256(F, 12.0) for F in (1.0, 1.1, 1.3)}
print('| room | n | current | physical f/1.0 | f/1.1 | f/1.3 | current + filter 0.9 | f/1.1 + filter 0.9 |')
for name in ['pr_full', 'oo_full', 'mr_full']:
    d = np.load(name + '.npz'); m = np.where(d['spread_png'] >= 2)[0]
    noise = [d['png'][i] - g(d['Ttrue'][i], 0.5) for i in m]   # the simulator's own noise field (approx.: its Gaussian is applied to radiance)
    cur = [realism_slope(d['png'][i]) for i in m]
    out = []
    for F in (1.0, 1.1, 1.3):
        out.append([realism_slope(filt(d['Ttrue'][i], Ms[F]) + n) for i, n in zip(m, noise)])
    cf = [realism_slope(g(d['png'][i], 0.9)) for i in m]
    pf = [realism_slope(g(filt(d['Ttrue'][i], Ms[1.1]) + n, 0.9)) for i, n in zip(m, noise)]
    print('| %s | %d | %.2f | %.2f | %.2f | %.2f | %.2f | %.2f |' % (name, len(m), np.median(cur), *[np.median(o) for o in out], np.median(cf), np.median(pf)))
