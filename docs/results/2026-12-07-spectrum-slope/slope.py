"""Spectrum-slope statistic of hoilcd realism (bench/realism/src/frame_statistics.cpp), in numpy.

stretched(): 1st..99th percentile -> 0..255 (float, clipped), resize to 256x192 INTER_AREA, round to u8.
slope(): mean removed, |DFT|^2 averaged over rings 1/256 cycles/px wide (ring = round(f/(1/256))),
least-squares slope of ln power vs ln f over rings 1/64..1/4 cycles/px.
Generalised: slope(img, lo, hi, ring) for any band, and native() which stretches without resizing.
"""
import glob
import os
import sys

import cv2
import numpy as np

W, H = 256, 192


def stretch_float(t):
    t = np.asarray(t, np.float32)
    p1, p99 = np.quantile(t.astype(np.float64), [0.01, 0.99])
    if not p99 > p1:
        return np.zeros_like(t)
    s = (t.astype(np.float32) * np.float32(255.0 / (p99 - p1)) - np.float32(p1 * 255.0 / (p99 - p1)))
    return np.clip(s, 0, 255).astype(np.float32)


def stretched(t, size=(W, H), interp=cv2.INTER_AREA, to_u8=True):
    s = stretch_float(t)
    if size is not None and (s.shape[1], s.shape[0]) != tuple(size):
        s = cv2.resize(s, size, interpolation=interp)
    if to_u8:
        return np.rint(s).clip(0, 255).astype(np.uint8)
    return s


def ring_spectrum(img, ring=1.0 / 256):
    f = img.astype(np.float64)
    f = f - f.mean()
    P = np.abs(np.fft.fft2(f)) ** 2
    h, w = f.shape
    fy = np.fft.fftfreq(h)[:, None]
    fx = np.fft.fftfreq(w)[None, :]
    # cv: y <= h/2 ? y : y-h  -> at y == h/2 the frequency is +0.5 (fftfreq gives -0.5; hypot same)
    r = np.rint(np.hypot(fx, fy) / ring).astype(int)
    n = int(np.rint(0.5 * np.sqrt(2) / ring)) + 2
    pw = np.bincount(r.ravel(), P.ravel(), minlength=n)
    ct = np.bincount(r.ravel(), minlength=n)
    freq = np.arange(len(pw)) * ring
    with np.errstate(invalid="ignore", divide="ignore"):
        mp = pw / ct
    return freq, mp, ct


def slope(img, lo=1.0 / 64, hi=1.0 / 4, ring=1.0 / 256):
    freq, mp, ct = ring_spectrum(img, ring)
    m = (freq >= lo - 1e-12) & (freq <= hi + 1e-12) & (ct > 0)
    if np.any(mp[m] <= 0):
        return np.nan
    return np.polyfit(np.log(freq[m]), np.log(mp[m]), 1)[0]


def realism_slope(t):
    return slope(stretched(t))


def load_real(d):
    out = []
    for p in sorted(glob.glob(os.path.join(d, "*.npy"))):
        a = np.load(p).astype(np.float32)
        if a.ndim == 3:
            a = a[..., 0]
        out.append((os.path.basename(p), a))
    return out


def source_of(name):
    if name.startswith("berrada99"):
        return "berrada99 (E8xt)"
    if name.startswith("thermitage"):
        return "Thermitage (WIRIS)"
    if name.startswith("palanithanarajk"):
        return "palanithanarajk (E54)"
    return "IRimage (Wikimedia)"


def spread(t):
    p5, p95 = np.quantile(t, [0.05, 0.95])
    return p95 - p5


def load_dataset(path, every=5, channel=None, start=0):
    """Frames of a hoilcd dataset: radiometric PNG (centikelvin, as realism reads it) or an EXR channel."""
    frames = []
    if channel is None:
        files = sorted(glob.glob(os.path.join(path, "radiometric", "*.png")))
        for f in files[start::every]:
            a = cv2.imread(f, cv2.IMREAD_UNCHANGED).astype(np.float64) / 100.0 - 273.15
            frames.append(a.astype(np.float32))
        return frames
    sys.path.insert(0, "/work/main/build/python")
    import hoilcd
    ds = hoilcd.Dataset(path, False)
    for i in range(start, len(ds), every):
        frames.append(np.asarray(ds.exr(i)[channel], np.float32))
    return frames
