import sys, numpy as np, json, collections
sys.path.insert(0, '/tmp/slope')
from slope import *
def flat_blocks(t, b=16, frac=0.1):
    t = t.astype(np.float64); h, w = t.shape
    yy, xx = np.mgrid[0:b, 0:b]; A = np.c_[np.ones(b * b), xx.ravel(), yy.ravel(), (xx**2).ravel(), (yy**2).ravel(), (xx*yy).ravel()]
    res = []
    for y in range(0, h - b + 1, b):
        for x in range(0, w - b + 1, b):
            blk = t[y:y + b, x:x + b].ravel()
            c, *_ = np.linalg.lstsq(A, blk, rcond=None)
            r = (blk - A @ c).reshape(b, b); res.append((r.std(), r))
    res.sort(key=lambda z: z[0])
    return [r for _, r in res[:max(1, int(len(res) * frac))]]
def acf(blocks):
    out = {}
    for name, (dy, dx) in {'x1': (0, 1), 'x2': (0, 2), 'x3': (0, 3), 'y1': (1, 0), 'y2': (2, 0), 'd1': (1, 1)}.items():
        num = den = 0
        for r in blocks:
            a = r[:r.shape[0] - dy, :r.shape[1] - dx]; b = r[dy:, dx:]
            num += (a * b).sum() / a.size; den += (r * r).sum() / r.size
        out[name] = num / den
    return out
groups = collections.defaultdict(list)
for n, a in load_real('/work/real_frames/all'):
    if spread(a) < 2: continue
    g = source_of(n) if not source_of(n).startswith('IRimage') else n[:30]
    groups[g] += flat_blocks(a)
d = np.load('pr_full.npz'); nb = np.where(d['spread_png'] >= 2)[0][::3]
for i in nb: groups['ours full (PNG)'] += flat_blocks(d['png'][i])
for g, b in groups.items():
    a = acf(b); print('%-32s blocks %4d  sigma %.4f K  ' % (g, len(b), np.median([r.std() for r in b])) + '  '.join('%s %.2f' % kv for kv in a.items()))
