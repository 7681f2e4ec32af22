"""extract.py DATASET OUT.npz [--keep]: every 5th frame: T (EXR), T_true, radiometric PNG (as realism reads),
Z median over the central 1/3 x 1/3 and the class there. Saves slopes; with --keep also the frames."""
import sys, numpy as np, cv2, glob, os
sys.path.insert(0, '/tmp/slope'); sys.path.insert(0, '/work/main/build/python')
from slope import *
import hoilcd
path, out = sys.argv[1], sys.argv[2]
keep = '--keep' in sys.argv
ds = hoilcd.Dataset(path, False)
files = sorted(glob.glob(os.path.join(path, 'radiometric', '*.png')))
rec = {k: [] for k in ['frame', 'slope_T', 'slope_Ttrue', 'slope_png', 'spread_png', 'spread_Ttrue', 'zc', 'zall', 'far_share']}
T, TT, PNG, Z = [], [], [], []
for i in range(0, len(ds), 5):
    e = ds.exr(i)
    t, tt, z = [np.asarray(e[c], np.float32) for c in ('T', 'T_true', 'Z')]
    p = (cv2.imread(files[i], cv2.IMREAD_UNCHANGED).astype(np.float64) / 100.0 - 273.15).astype(np.float32)
    h, w = z.shape
    zc = z[h // 3:2 * h // 3, w // 3:2 * w // 3]
    rec['frame'].append(i)
    rec['slope_T'].append(realism_slope(t)); rec['slope_Ttrue'].append(realism_slope(tt)); rec['slope_png'].append(realism_slope(p))
    rec['spread_png'].append(spread(p)); rec['spread_Ttrue'].append(spread(tt))
    zf = z[np.isfinite(z)]
    rec['zc'].append(float(np.nanmedian(zc))); rec['zall'].append(float(np.median(zf)) if zf.size else np.nan)
    rec['far_share'].append(float(np.mean(zf > 2.5)) if zf.size else np.nan)
    if keep:
        T.append(t); TT.append(tt); PNG.append(p); Z.append(z.astype(np.float16))
d = {k: np.array(v) for k, v in rec.items()}
if keep:
    d.update(T=np.array(T), Ttrue=np.array(TT), png=np.array(PNG), Z=np.array(Z))
np.savez(out, **d)
nb = d['spread_png'] >= 2
print(os.path.basename(path), 'frames', len(d['frame']), 'blank %.1f%%' % (100 * (1 - nb.mean())),
      'median slope (not blank): png %.3f  T %.3f  T_true %.3f' % tuple(np.median(d[k][nb]) for k in ('slope_png', 'slope_T', 'slope_Ttrue')))
