import json, numpy as np, sys
sys.path.insert(0,'/tmp/slope')
from slope import *
r=json.load(open('realism_pr_full/realism.json'))
real={p['frame']:p['spectrum_slope'] for p in r['real']['per_frame']}
d=[]
for n,a in load_real('/work/real_frames/all'):
    d.append(realism_slope(a)-real[n])
print('real max |diff|', np.max(np.abs(d)))
syn={int(p['frame']):p['spectrum_slope'] for p in r['synthetic']['per_frame']}
fr=load_dataset('pr_full',5)
d=[realism_slope(a)-syn[5*i] for i,a in enumerate(fr)]
print('syn max |diff|', np.max(np.abs(d)), len(fr), sorted(syn)[:5])
