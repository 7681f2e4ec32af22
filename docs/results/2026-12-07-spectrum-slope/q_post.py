"""Post-process our default frames with a spatial filter as a camera's noise reduction would; slope and noise ACF."""
import sys, numpy as np, cv2
sys.path.insert(0, '/tmp/slope'); from slope import *
sys.argv = ['x']; exec(open('/tmp/slope/q_acf.py').read().split('groups = ')[0])  # flat_blocks, acf
d = np.load('pr_full.npz'); m = np.where(d['spread_png'] >= 2)[0]
B = [(1/64, 1/32), (1/32, 1/16), (1/16, 1/8), (1/8, 1/4)]
print('sigma  slope_med  d_vs_default  sub-bands(64-32,32-16,16-8,8-4)  noise_sigma_K  acf_x1 x2 x3')
base = None
for s in [0, 0.5, 0.7, 0.8, 0.9, 1.0, 1.2]:
    sl, sb, blocks = [], [], []
    for i in m:
        a = d['png'][i].astype(np.float32)
        f = cv2.GaussianBlur(a, (0, 0), s, borderType=cv2.BORDER_REFLECT) if s > 0 else a
        st = stretched(f); sl.append(slope(st)); sb.append([slope(st, lo, hi) for lo, hi in B])
        if i % 3 == 0: blocks += flat_blocks(f)
    sl = np.array(sl)
    if base is None: base = sl
    a_ = acf(blocks)
    print('%.1f  %.3f  %+.3f  %s  %.4f  %.2f %.2f %.2f' % (s, np.median(sl), np.median(sl - base), ' '.join('%.2f' % x for x in np.median(sb, 0)),
          np.median([r.std() for r in blocks]), a_['x1'], a_['x2'], a_['x3']))
