import numpy as np, sys
sys.path.insert(0,'/tmp/slope'); from slope import *
full = np.load('pr_full.npz'); blur = np.load('pr_only_optics_blur.npz'); none = np.load('pr_none.npz')
sp = full['spread_png']
print('ours: effect of noise+FPN+rest (full - only_blur) and of blur (only_blur - none) by p95-p5 spread')
for lo, hi in [(2, 4), (4, 8), (8, 100)]:
    m = (sp >= lo) & (sp < hi)
    print(' spread %g-%g K: n %3d  full %.3f  noise effect %+.3f  blur effect %+.3f' % (lo, hi, m.sum(), np.median(full['slope_png'][m]),
          np.median(full['slope_png'][m] - blur['slope_png'][m]), np.median(blur['slope_png'][m] - none['slope_png'][m])))
rs = [(spread(a), realism_slope(a), source_of(n)) for n, a in load_real('/work/real_frames/all')]
print('real: by spread')
for lo, hi in [(2, 4), (4, 8), (8, 100)]:
    v = [s for sp_, s, src in rs if lo <= sp_ < hi]
    print(' spread %g-%g K: n %2d  median slope %.3f' % (lo, hi, len(v), np.median(v) if v else np.nan))
print('real spread median (not blank) %.2f K, ours %.2f K' % (np.median([a for a, s, _ in rs if a >= 2]), np.median(sp[sp >= 2])))
