"""Q4: slope by distance of the wall ahead (median EXR depth over the central third of the image) and by wall share."""
import sys, numpy as np, json
sys.path.insert(0, '/tmp/slope'); from slope import *
def wall_share(t):
    return float(np.mean(np.abs(t - np.median(t)) <= 1.5))
for f in sys.argv[1:]:
    d = np.load(f)
    sp, sl, zc = d['spread_png'], d['slope_png'], d['zc']
    nb = sp >= 2
    print('==', f, 'frames', len(sp), 'not blank', nb.sum(), 'median slope (not blank) %.3f' % np.median(sl[nb]))
    for lo, hi in [(0, 1), (1, 2.5), (2.5, 99)]:
        m = (zc >= lo) & (zc < hi)
        print('  wall ahead %4.1f-%4.1f m: views %3d, blank %5.1f%%, slope not blank: n %3d median %s' % (lo, hi, m.sum(), 100 * np.mean(~nb[m]) if m.sum() else np.nan,
              (m & nb).sum(), '%.3f' % np.median(sl[m & nb]) if (m & nb).sum() else '-'))
    if 'png' in d.files:
        ws = np.array([wall_share(t) for t in d['png']])
        for lo, hi in [(0, 0.6), (0.6, 0.8), (0.8, 1.01)]:
            m = (ws >= lo) & (ws < hi) & nb
            print('  wall share %.1f-%.1f: n %3d median slope %s' % (lo, hi, m.sum(), '%.3f' % np.median(sl[m]) if m.sum() else '-'))
if len(sys.argv) > 1 and sys.argv[1] == 'pr_full.npz' or True:
    pass
