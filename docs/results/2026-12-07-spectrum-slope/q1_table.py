import numpy as np, glob
base = np.load('pr_none.npz'); full = np.load('pr_full.npz')
mask = full['spread_png'] >= 2
print('mask: %d of %d frames not blank in the default render' % (mask.sum(), len(mask)))
rows = [('none (all sensor effects off)', 'pr_none'), ('T_true channel of the default render', None)] + \
       [(n, f'pr_{n}') for n in ['only_optics_blur', 'only_temporal_noise', 'only_fixed_pattern', 'only_quantisation', 'only_time_constant', 'only_lowfreq',
                                  'but_optics_blur', 'but_temporal_noise', 'but_fixed_pattern', 'but_quantisation']] + [('full (defaults)', 'pr_full')]
b = base['slope_png'][mask]
for name, f in rows:
    if f is None:
        s = full['slope_Ttrue'][mask]
    else:
        s = np.load(f + '.npz')['slope_png'][mask]
    d = s - b
    print('%-40s median %.3f  mean %.3f  paired diff vs none: median %+.3f  mean %+.3f' % (name, np.median(s), np.mean(s), np.median(d), np.mean(d)))
