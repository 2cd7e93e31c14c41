#!/usr/bin/python3
"""The 4:2:0 shift of each edge line predicted by inverting the codec on the line's own profile
(a numpy experiment, docs/notes/issue12_jpeg_chroma.md).

Usage: /usr/bin/python3 tests/bench/chroma_deconvolution_probe.py PNG_DUMP DECODED_DUMP ITERATIONS EVERY

PNG_DUMP and DECODED_DUMP are `edge_bias_probe --dump` files (20 frames) of a PNG sequence and of
its 4:2:0-only copy measured as 4:4:4 (`jpeg_variants.py SRC DST subsample`, `--set
edge.chroma_sampling=4:4:4`). For every EVERY-th line the decoded profile is taken as a first
guess of the profile before the codec; the guess is drawn as a patch constant along the line's
tangent (on the image's own 2x2 grid), passed through 4:2:0 (JFIF Y'CbCr, 2x2 chroma means,
libjpeg's fancy upsampling), sampled back along the line, and corrected by the difference to the
decoded profile, ITERATIONS times (a Van Cittert inversion). Both profiles are fitted with the edge
stage's six-parameter model from the steepest descent; the predicted shift is μ(decoded) −
μ(inverted), the true shift μ(decoded) − μ(PNG). Prints their means per camera and rim, also over
the lines within 0.4 px of the true contour (core), and their correlation.
"""
import os
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
sys.path.insert(0, os.path.join(HERE, '..', '..', 'scripts', 'pbr'))
from edge_sliver_fit import model_a as step_model  # noqa: E402
from jpeg_block_edge_fit import lm  # noqa: E402
import jpeg_variants as jv  # noqa: E402
import pbr_common as pc  # noqa: E402

S = np.arange(-16, 17) * 0.25  # the dump's sample offsets (px)


def fit_mean(profile, direction):
    """μ of the six-parameter fit of the projected profile from its steepest descent in ±2 px."""
    p = profile @ direction
    search = np.abs(S[:-1]) <= 2.0
    k = int(np.argmin(np.where(search, np.diff(p), np.inf)))
    mu0 = 0.5 * (S[k] + S[k + 1])
    window = np.abs(S - mu0) <= 2.5
    s_w, p_w = S[window], p[window]
    q, _ = lm(lambda q: step_model(q, s_w) - p_w,
              [p_w[0], 0.0, p_w[-1] - p_w[0], mu0, np.log(0.7), 0.0], [1e-4] * 6, watch=3)
    return q[3]


def contrast_direction(profile):
    d = profile[S <= -1].mean(0) - profile[S >= 1].mean(0)
    d[profile.max(0) >= 0.95] = 0.0
    norm = np.linalg.norm(d)
    return None if norm < 0.01 else d / norm


def through_codec(profile, centre, normal, reach=8):
    """The line's linear-RGB profile drawn as a patch constant along the tangent, through 4:2:0,
    sampled back bilinearly at the same offsets."""
    x0 = int(np.floor(centre[0])) - reach
    y0 = int(np.floor(centre[1])) - reach
    x0 -= x0 % 2
    y0 -= y0 % 2
    ys, xs = np.mgrid[y0:y0 + 2 * reach + 2, x0:x0 + 2 * reach + 2]
    s = (xs - centre[0]) * normal[0] + (ys - centre[1]) * normal[1]
    linear = np.stack([np.interp(s, S, profile[:, c]) for c in range(3)], -1)
    y, cb, cr = jv.to_ycbcr(255.0 * pc.srgb_encode(linear)[..., ::-1])
    decoded = jv.to_bgr_float(y, jv.fancy_upsample(jv.mean2x2(cb)),
                              jv.fancy_upsample(jv.mean2x2(cr)))[..., ::-1]
    decoded = pc.srgb_to_linear(np.clip(decoded, 0, 255))
    out = np.zeros_like(profile)
    for i, offset in enumerate(S):
        px = centre[0] + offset * normal[0] - x0
        py = centre[1] + offset * normal[1] - y0
        ix, iy = int(np.floor(px)), int(np.floor(py))
        fx, fy = px - ix, py - iy
        out[i] = ((1 - fy) * ((1 - fx) * decoded[iy, ix] + fx * decoded[iy, ix + 1]) +
                  fy * ((1 - fx) * decoded[iy + 1, ix] + fx * decoded[iy + 1, ix + 1]))
    return out


def load(path, frames=20):
    lines = {}
    with open(path) as f:
        for row in f:
            v = row.split()
            if int(v[1]) >= frames:
                continue
            key = (v[0], int(v[1]), round(float(v[3]), 2), round(float(v[4]), 2))
            lines[key] = (v[2], np.array(v[9:108], float).reshape(33, 3),
                          np.array([float(v[3]), float(v[4])]), np.array([float(v[5]), float(v[6])]))
    return lines


def main():
    if len(sys.argv) != 5:
        sys.exit(__doc__)
    png, decoded = load(sys.argv[1]), load(sys.argv[2])
    iterations, every = int(sys.argv[3]), int(sys.argv[4])
    rows = []
    for n, (key, (rim, profile, centre, normal)) in enumerate(decoded.items()):
        if n % every or key not in png:
            continue
        direction = contrast_direction(profile)
        if direction is None:
            continue
        guess = profile.copy()
        for _ in range(iterations):
            guess = np.clip(guess + profile - through_codec(guess, centre, normal), 0.0, 1.0)
        rows.append((key[0], rim, fit_mean(png[key][1], direction), fit_mean(profile, direction),
                     fit_mean(guess, direction)))
    for camera in ["cam0", "cam1"]:
        for rim in ["up", "down", "left", "right"]:
            a = np.array([r[2:] for r in rows if r[0] == camera and r[1] == rim])
            if len(a) < 10:
                continue
            a = a[np.all(np.abs(a) < 2.2, axis=1)]
            true, predicted = a[:, 1] - a[:, 0], a[:, 1] - a[:, 2]
            core = np.abs(a[:, 0]) < 0.4
            print(f"{camera} {rim:5s} n={len(a):4d} true {true.mean():+.3f} "
                  f"predicted {predicted.mean():+.3f} | core n={core.sum()} "
                  f"true {true[core].mean():+.3f} predicted {predicted[core].mean():+.3f} | "
                  f"correlation {np.corrcoef(true, predicted)[0, 1]:+.2f}")


if __name__ == "__main__":
    with np.errstate(all="ignore"):
        main()
