#!/usr/bin/python3
"""Does the image far outside a rim (what a grazing reflection would mirror, if the room behind
the object were far away) predict where the edge stage finds the rim? (docs/notes/
issue12_rim_shading.md, "The mirrored environment read from the image").

Reads an `edge_bias_probe --dump` file (lines at the true pose) and the sequence's images. Per
line: the inside level A (1-4 px in), the near background B (1-4 px out) and the mean colour E
of bands farther out along the normal, all linear (sRGB decoded); the contrast direction
d = (A - B) over the unclipped channels. A sliver of width eps mirroring E moves the fitted
step by mu = -eps (A - E).d / (A - B).d, so q = -(A - E).d / (A - B).d per band is the
predicted offset per px of sliver. Prints per camera and rim the mean mu and mean q per band,
and per camera the correlation of mu with q and the least-squares fit mu = c0 + c1 q.

Usage: tests/bench/rim_environment_correlation.py SEQ DUMP. Not a test.
"""
import sys, os
import numpy as np, cv2

seq, dump = sys.argv[1], sys.argv[2]
bands = [(1, 4), (4, 10), (10, 25), (25, 60), (60, 150)]
imgs = {}
def image(cam, f):
    k = (cam, f)
    if k not in imgs:
        p = os.path.join(seq, cam, f"{f:06d}.png")
        if not os.path.exists(p): p = p[:-4] + ".jpg"
        im = cv2.imread(p, cv2.IMREAD_COLOR)[:, :, ::-1].astype(np.float64) / 255.0
        lin = np.where(im <= 0.04045, im / 12.92, ((im + 0.055) / 1.055) ** 2.4)
        imgs[k] = lin
    return imgs[k]

def sample(im, pts):
    h, w, _ = im.shape
    x = np.clip(pts[:, 0], 0, w - 1.001); y = np.clip(pts[:, 1], 0, h - 1.001)
    x0 = np.floor(x).astype(int); y0 = np.floor(y).astype(int); fx = (x - x0)[:, None]; fy = (y - y0)[:, None]
    return ((1 - fx) * (1 - fy) * im[y0, x0] + fx * (1 - fy) * im[y0, x0 + 1] + (1 - fx) * fy * im[y0 + 1, x0] + fx * fy * im[y0 + 1, x0 + 1])

rows = []
for text in open(dump):
    t = text.split()
    cam, f, rim = t[0], int(t[1]), t[2]
    cx, cy, nx, ny, mu, sig = map(float, t[3:9])
    im = image(cam, f)
    c = np.array([cx, cy]); n = np.array([nx, ny])
    def band_mean(a, b, inside=False):
        s = np.arange(a, b + 0.01, 0.5)
        pts = c[None] + (-s if inside else s)[:, None] * n[None]
        return sample(im, pts).mean(0)
    A = band_mean(1, 4, inside=True)
    Es = [band_mean(a, b) for a, b in bands]
    B = Es[0]
    peak = np.maximum(A, B)
    d = (A - B) * (peak < 0.95)
    b = np.linalg.norm(d)
    if b < 0.02: continue
    d /= b
    q = [(-(A - E) @ d) / b for E in Es]   # predicted mu / eps for a sliver mirroring E
    rows.append((cam, rim, mu, max(sig, 0.1), *q))

cams = sorted(set(r[0] for r in rows))
print("per camera and rim: n, mean mu, and mean q per band", bands)
for cam in cams:
    for rim in ["up", "down", "left", "right"]:
        sel = [r for r in rows if r[0] == cam and r[1] == rim]
        if not sel: continue
        a = np.array([r[2:] for r in sel])
        print(f"{cam} {rim:5s} n={len(sel):5d} mu={a[:,0].mean():+.3f} " + " ".join(f"{v:+.3f}" for v in a[:, 2:].mean(0)))
print("correlation of mu with q per band (all lines; robust: mu clipped to +-1.5)")
for cam in cams:
    a = np.array([r[2:] for r in rows if r[0] == cam])
    mu = np.clip(a[:, 0], -1.5, 1.5)
    cs = [np.corrcoef(mu, np.clip(a[:, 2 + i], -3, 3))[0, 1] for i in range(len(bands))]
    # least squares mu = c0 + c1 q per band
    fits = []
    for i in range(len(bands)):
        q = np.clip(a[:, 2 + i], -3, 3)
        X = np.c_[np.ones_like(q), q]
        coef = np.linalg.lstsq(X, mu, rcond=None)[0]
        fits.append(coef)
    print(cam, " ".join(f"r={c:+.3f} (c0 {k[0]:+.3f}, c1 {k[1]:+.3f})" for c, k in zip(cs, fits)))
