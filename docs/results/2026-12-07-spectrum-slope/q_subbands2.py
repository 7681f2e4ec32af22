"""Octave sub-band slopes (realism size): real sources, ours current, ours with the physical pixel response (f/1.1)."""
import sys, numpy as np, collections
sys.path.insert(0, '/tmp/slope'); from slope import *
exec(open('/tmp/slope/q_rooms.py').read().split('Ms = ')[0].split('exec(')[0])
exec('def planck_w' + open('/tmp/slope/q_rooms.py').read().split('def planck_w')[1].split('Ms = ')[0])
M = mtf256(1.1, 12.0)
B = [(1/64, 1/32), (1/32, 1/16), (1/16, 1/8), (1/8, 1/4), (1/64, 1/4)]
def sub(img): return [slope(img, lo, hi) for lo, hi in B]
rows = collections.defaultdict(list)
for n, a in load_real('/work/real_frames/all'):
    if spread(a) < 2: continue
    if a.shape[1] < 256: continue   # upsampled frames left out
    rows[source_of(n)].append(sub(stretched(a)))
for name in ['pr_full', 'oo_full', 'mr_full']:
    d = np.load(name + '.npz'); m = np.where(d['spread_png'] >= 2)[0]
    for i in m:
        rows[name + ' current'].append(sub(stretched(d['png'][i])))
        nz = d['png'][i] - g(d['Ttrue'][i], 0.5)
        rows[name + ' physical f/1.1'].append(sub(stretched(filt(d['Ttrue'][i], M) + nz)))
print('| set | n | 64-32 px | 32-16 | 16-8 | 8-4 | whole band (IQR) |')
for k, v in rows.items():
    v = np.array(v); q1, q3 = np.nanpercentile(v[:, -1], [25, 75])
    print('| %s | %d | ' % (k, len(v)) + ' | '.join('%.2f' % x for x in np.nanmedian(v[:, :4], 0)) + ' | %.2f (%.2f to %.2f) |' % (np.nanmedian(v[:, -1]), q1, q3))
