"""Addendum (revision 22): the physical MTF applied with a periodic FFT (as q_mtf.py and q_mtf2.py did) against the
same MTF applied with the frame mirrored at its borders (a mirrored FFT, and the DCT-II the simulator now uses),
on T_true of a revision-22 paper_room run (extract.py DATASET pr22.npz --keep). Usage: python3 q_wrap.py pr22.npz"""
import sys, numpy as np, cv2
sys.path.insert(0, '/tmp/slope'); from slope import *
d = np.load(sys.argv[1]); nb = d['spread_png'] >= 2
h, c, k = 6.62607015e-34, 299792458.0, 1.380649e-23
lam = np.linspace(8, 14, 49); w = np.ones(49); w[1:-1:2] = 4; w[2:-1:2] = 2
w = w * (2 * h * c * c / (lam * 1e-6) ** 5 / np.expm1(h * c / (lam * 1e-6 * k * 300.0))); w /= w.sum()
def mtf(fx, fy, N=1.1, p=12.0):
    f = np.hypot(fx, fy); m = 0
    for l, wt in zip(lam, w):
        nu = np.clip(f * l * N / p, 0, 1); m = m + wt * (2 / np.pi) * (np.arccos(nu) - nu * np.sqrt(1 - nu * nu))
    return m * np.sinc(fx) * np.sinc(fy)
Mw = mtf(np.fft.fftfreq(256)[None, :], np.fft.fftfreq(192)[:, None])
Mm = mtf(np.fft.fftfreq(512)[None, :], np.fft.fftfreq(384)[:, None])
G = mtf(np.arange(256)[None, :] / 512.0, np.arange(192)[:, None] / 384.0).astype(np.float32)
res = {'T_true': [], 'periodic FFT': [], 'mirrored FFT': [], 'DCT-II (the simulator)': [], 'simulator output T': []}
for i in np.where(nb)[0]:
    tt = d['Ttrue'][i].astype(np.float64)
    ext = np.block([[tt, tt[:, ::-1]], [tt[::-1, :], tt[::-1, ::-1]]])
    res['T_true'].append(realism_slope(tt.astype(np.float32)))
    res['periodic FFT'].append(realism_slope(np.real(np.fft.ifft2(np.fft.fft2(tt) * Mw)).astype(np.float32)))
    res['mirrored FFT'].append(realism_slope(np.real(np.fft.ifft2(np.fft.fft2(ext) * Mm))[:192, :256].astype(np.float32)))
    res['DCT-II (the simulator)'].append(realism_slope(cv2.idct(cv2.dct(tt.astype(np.float32)) * G)))
    res['simulator output T'].append(realism_slope(d['T'][i]))
for key, v in res.items(): print('%-26s n %d  median slope %.3f' % (key, len(v), np.median(v)))
