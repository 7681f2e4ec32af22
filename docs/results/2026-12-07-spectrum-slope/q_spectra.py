"""Mean ring spectra (native resolution, stretched float) per source and for our frames; noise estimates in K."""
import sys, numpy as np, cv2, json, collections
sys.path.insert(0, '/tmp/slope')
from slope import *
def immerkaer(t):  # Immerkaer 1996 fast noise variance estimation, white-noise sigma in the image's unit
    M = np.array([[1, -2, 1], [-2, 4, -2], [1, -2, 1]], np.float64)
    c = cv2.filter2D(t.astype(np.float64), -1, M, borderType=cv2.BORDER_REFLECT)[1:-1, 1:-1]
    return np.sqrt(np.pi / 2) * np.mean(np.abs(c)) / 6
def flat_noise(t, b=16):
    """Noise from the flattest blocks: residual std after a plane fit, median over the 10 % lowest-gradient blocks;
    also the ratio of high-band to mid-band power of those residuals (1 for white noise)."""
    t = t.astype(np.float64); h, w = t.shape
    yy, xx = np.mgrid[0:b, 0:b]; A = np.c_[np.ones(b * b), xx.ravel(), yy.ravel()]
    res = []
    for y in range(0, h - b + 1, b):
        for x in range(0, w - b + 1, b):
            blk = t[y:y + b, x:x + b].ravel()
            c, *_ = np.linalg.lstsq(A, blk, rcond=None)
            r = (blk - A @ c).reshape(b, b)
            res.append((r.std(), r))
    res.sort(key=lambda z: z[0])
    sel = res[:max(1, len(res) // 10)]
    P = np.mean([np.abs(np.fft.fft2(r)) ** 2 for _, r in sel], axis=0)
    f = np.hypot(np.fft.fftfreq(b)[:, None], np.fft.fftfreq(b)[None, :])
    hi = P[(f >= 0.35) & (f <= 0.5)].mean(); mid = P[(f >= 0.1) & (f < 0.2)].mean()
    return float(np.median([s for s, _ in sel])), float(hi / mid)
out = collections.defaultdict(list)
for n, a in load_real('/work/real_frames/all'):
    if spread(a) < 2: continue
    s = stretched(a, size=None, to_u8=False)
    fr, mp, ct = ring_spectrum(s, 1 / 64)
    nz, ratio = flat_noise(a)
    out[source_of(n)].append(dict(name=n, shape=a.shape, imm=immerkaer(a), flat=nz, hi_mid=ratio, fr=fr.tolist(), mp=mp.tolist()))
for name, fname, ch in [('ours full (PNG)', 'pr_full.npz', 'png'), ('ours T_true', 'pr_full.npz', 'Ttrue')]:
    d = np.load(fname)
    nb = d['spread_png'] >= 2
    for i in np.where(nb)[0][::2]:
        a = d[ch][i]
        s = stretched(a, size=None, to_u8=False)
        fr, mp, ct = ring_spectrum(s, 1 / 64)
        nz, ratio = flat_noise(a)
        out[name].append(dict(name=str(i), shape=a.shape, imm=immerkaer(a), flat=nz, hi_mid=ratio, fr=fr.tolist(), mp=mp.tolist()))
json.dump(out, open('q_spectra.json', 'w'))
print('source  n  immerkaer_sigma_K  flat_block_sigma_K  flat_hi/mid_power')
for k, v in out.items():
    print(k, len(v), '%.4f %.4f %.3f' % tuple(np.median([r[c] for r in v]) for c in ('imm', 'flat', 'hi_mid')))
