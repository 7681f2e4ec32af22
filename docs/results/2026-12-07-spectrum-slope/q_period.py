"""Is the E8xt's noise correlation stationary (a filter) or periodic (an upsampled lower-resolution image)?
Lag-1 correlation of flat-region residuals at even vs odd columns/rows, on the high-pass of the whole frame."""
import sys, numpy as np, cv2
sys.path.insert(0, '/tmp/slope')
from slope import *
def hp(a):
    a = a.astype(np.float64)
    return a - cv2.GaussianBlur(a, (0, 0), 3)
for src in ['berrada99', '25_', '09_', 'thermitage', '10_']:
    ex = [[], []]; ey = [[], []]; var = []
    for n, a in load_real('/work/real_frames/all'):
        if not n.startswith(src) or spread(a) < 2: continue
        r = hp(a)
        g = np.hypot(*np.gradient(cv2.GaussianBlur(a.astype(np.float64), (0, 0), 2)))
        m = g < np.quantile(g, 0.3)  # flattest 30 % of pixels
        for par in (0, 1):
            mm = m[:, par:-1:2] & m[:, par + 1::2]
            ex[par].append((r[:, par:-1:2] * r[:, par + 1::2])[mm].mean() / (r[m] ** 2).mean())
            mm = m[par:-1:2, :] & m[par + 1::2, :]
            ey[par].append((r[par:-1:2, :] * r[par + 1::2, :])[mm].mean() / (r[m] ** 2).mean())
    print('%-12s x-lag1 even %.2f odd %.2f | y-lag1 even %.2f odd %.2f' % (src, np.median(ex[0]), np.median(ex[1]), np.median(ey[0]), np.median(ey[1])))
