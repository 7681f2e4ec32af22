"""Q2: real slopes at the realism size (256x192 INTER_AREA) vs native resolution, and band matched in cycles/degree."""
import sys, numpy as np, cv2, json
sys.path.insert(0, '/tmp/slope')
from slope import *
# native px per degree of horizontal FOV (FOV from each file's FLIR/EXIF record; ours from the scene)
HFOV = {'berrada99': 45.0, 'thermitage': 45.4, 'palanithanarajk': 23.5, '02': 23.8, '09': 23.1, '10': 25.0, '22': 25.0, '25': 25.0}
OURS_PX_PER_DEG = 256 / 50.0
LO_DEG, HI_DEG = OURS_PX_PER_DEG / 64, OURS_PX_PER_DEG / 4   # our band in cycles/deg
def key(n):
    for k in HFOV:
        if n.startswith(k): return k
rows = []
for n, a in load_real('/work/real_frames/all'):
    h, w = a.shape
    ppd = w / HFOV[key(n)]
    r = dict(name=n, src=source_of(n), shape=f'{w}x{h}', ppd=ppd, blank=bool(spread(a) < 2))
    r['realism'] = realism_slope(a)
    r['area_u8_float'] = slope(stretched(a, to_u8=False))
    nat = stretched(a, size=None)
    r['native'] = slope(nat)
    r['native_float'] = slope(stretched(a, size=None, to_u8=False))
    # nearest / linear resize instead of INTER_AREA
    r['linear256'] = slope(stretched(a, interp=cv2.INTER_LINEAR))
    r['nearest256'] = slope(stretched(a, interp=cv2.INTER_NEAREST))
    # band matched in cycles per degree, at native sampling
    r['native_degband'] = slope(nat, LO_DEG / ppd, HI_DEG / ppd)
    # resampled to our angular sampling (5.12 px/deg) with INTER_AREA, our band
    s = OURS_PX_PER_DEG / ppd
    sz = (max(8, int(round(w * s))), max(8, int(round(h * s))))
    r['ours_ppd'] = slope(stretched(a, size=sz)) if s < 1 else np.nan
    r['ours_ppd_size'] = f'{sz[0]}x{sz[1]}'
    rows.append(r)
json.dump(rows, open('q2_real.json', 'w'), indent=1)
import collections
g = collections.defaultdict(list)
for r in rows:
    if not r['blank']: g[r['src']].append(r); g['all real'].append(r)
cols = ['realism', 'area_u8_float', 'native', 'native_float', 'linear256', 'nearest256', 'native_degband', 'ours_ppd']
print('source n ' + ' '.join(cols))
for k, v in g.items():
    print(k, len(v), ' '.join('%.3f' % np.nanmedian([r[c] for r in v]) for c in cols))
for r in rows:
    if r['src'].startswith('IRimage'): print(r['name'], r['shape'], '%.2f' % r['ppd'], r['ours_ppd_size'], ' '.join('%.3f' % r[c] for c in cols))
