import sys, json, numpy as np, collections, cv2
sys.path.insert(0, '/tmp/slope'); from slope import *
rows = json.load(open('q2_real.json'))
HF = {'berrada99': 45.0, 'thermitage': 45.4, 'palanithanarajk': 23.5, '02': 23.8, '09': 23.1, '10': 25.0, '22': 25.0, '25': 25.0}
OURS = 256 / 50.0
data = dict(load_real('/work/real_frames/all'))
for r in rows:
    a = data[r['name']]; ppd = r['ppd']
    nat = stretched(a, size=None)
    r['native_content'] = slope(nat, OURS / 64 / ppd, OURS / 8 / ppd)     # 0.08-0.64 cyc/deg
    r['upsampled'] = a.shape[1] < 256
g = collections.defaultdict(list)
for r in rows:
    if r['blank']: continue
    g[r['src']].append(r); g['all real'].append(r)
cols = [('realism', 'realism 256x192 INTER_AREA'), ('linear256', 'INTER_LINEAR'), ('native', 'native px, 1/64-1/4 cyc/px'),
        ('native_degband', 'native px, 0.08-1.28 cyc/deg'), ('native_content', 'native px, 0.08-0.64 cyc/deg'), ('ours_ppd', 'resampled to 5.12 px/deg')]
print('| source | n | ' + ' | '.join(c[1] for c in cols) + ' |')
for k, v in g.items():
    vals = []
    for c, _ in cols:
        x = [r[c] for r in v if not (c.startswith('native') and r['upsampled'])]
        vals.append('%.2f' % np.nanmedian(x) if len(x) else '-')
    print('| %s | %d | ' % (k, len(v)) + ' | '.join(vals) + ' |')
d = np.load('pr_full.npz'); m = d['spread_png'] >= 2
for ch in ['png', 'Ttrue']:
    s = [stretched(t) for t in d[ch][m]]
    print('| ours %s | %d | %.2f | = | = | = | %.2f | = |' % (ch, m.sum(), np.median([slope(x) for x in s]), np.median([slope(x, 1/64, 1/8) for x in s])))
print('upsampled frames (native width < 256):', [(r['name'], r['shape'], round(r['realism'], 2), round(r['native'], 2)) for r in rows if r['upsampled']])
