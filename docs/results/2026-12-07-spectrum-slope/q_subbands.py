"""Local slopes in octave sub-bands at the realism size, medians over views that are not blank."""
import sys, numpy as np, glob, collections
sys.path.insert(0, '/tmp/slope')
from slope import *
B = [(1/64, 1/32), (1/32, 1/16), (1/16, 1/8), (1/8, 1/4), (1/4, 1/2)]
def sub(img): return [slope(img, lo, hi) for lo, hi in B] + [slope(img)]
rows = collections.defaultdict(list)
for n, a in load_real('/work/real_frames/all'):
    if spread(a) < 2: continue
    rows[source_of(n)].append(sub(stretched(a)))
extra = sys.argv[1:] or ['pr_full.npz:png', 'pr_full.npz:Ttrue']
for spec in extra:
    f, ch = spec.split(':')
    d = np.load(f); nb = np.where(d['spread_png'] >= 2)[0]
    for i in nb: rows[spec].append(sub(stretched(d[ch][i])))
print('%-28s %4s ' % ('set', 'n') + ' '.join('%7s' % ('%g-%g' % (1/lo, 1/hi)) for lo, hi in B) + '   band')
for k, v in rows.items():
    print('%-28s %4d ' % (k, len(v)) + ' '.join('%7.2f' % x for x in np.nanmedian(np.array(v), 0)))
