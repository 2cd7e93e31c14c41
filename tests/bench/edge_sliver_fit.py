#!/usr/bin/python3
"""Edge lines refitted with a rim sliver in the profile model (a numpy experiment).

Usage: /usr/bin/python3 tests/bench/edge_sliver_fit.py DUMP CAMERA RIM [MAX_LINES]

DUMP is `edge_bias_probe --dump` at the true pose (s = 0 at the true contour; 33 linear-RGB
samples every 0.25 px from −4 to +4 px). Each line is projected on its contrast direction (inside
minus outside means over |s| >= 1 px, channels reaching 0.95 left out, as the edge stage does)
and fitted three ways:
- A, steepest: the edge stage's six-parameter model, r = a + g·s + b·Φ(z) + k·w·R(z),
  z = (s − μ)/w, on ±2.5 px around the steepest descent (where the edge stage starts);
- A from 0: the same model on the whole window, started at the true contour;
- B from 0: A plus a band of its own level c between μ − δ and μ, blurred like the step,
  c·(Φ((s − μ + δ)/w) − Φ(z)), on the whole window, started at the true contour;
- B after A: the same, started from A's steepest-descent solution, on A's window and on the
  whole window (where the edge stage would run it: it does not know the true contour).
Prints the mean, median, 10 % / 90 % quantiles of μ (px, + outward) and the share of lines more
than 0.4 px inside (docs/notes/issue12_rim_profiles.md, "A sliver in the model").
"""
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from jpeg_block_edge_fit import lm, phi  # noqa: E402

S = np.arange(-16, 17) * 0.25


def ramp(z):
    return z * phi(z) + np.exp(-0.5 * z * z) / np.sqrt(2 * np.pi)


def model_a(p, s):
    w = np.exp(np.clip(p[4], -4.0, 2.0))
    z = (s - p[3]) / w
    return p[0] + p[1] * s + p[2] * phi(z) + p[5] * w * ramp(z)


def model_b(p, s):
    w = np.exp(np.clip(p[4], -4.0, 2.0))
    delta = np.exp(np.clip(p[7], -4.0, 2.0))
    return model_a(p[:6], s) + p[6] * (phi((s - p[3] + delta) / w) - phi((s - p[3]) / w))


def project(profile):
    d = profile[S <= -1].mean(0) - profile[S >= 1].mean(0)
    d[profile.max(0) >= 0.95] = 0.0
    norm = np.linalg.norm(d)
    return None if norm < 0.01 else profile @ (d / norm)


def main():
    if len(sys.argv) < 4:
        sys.exit(__doc__)
    camera, rim = sys.argv[2], sys.argv[3]
    max_lines = int(sys.argv[4]) if len(sys.argv) > 4 else 400
    profiles = []
    with open(sys.argv[1]) as f:
        for row in f:
            v = row.split()
            if v[0] == camera and v[2] == rim and len(profiles) < max_lines:
                profiles.append(np.array(v[9:108], float).reshape(33, 3))
    results = []
    for profile in profiles:
        p = project(profile)
        if p is None:
            continue
        k = int(np.argmin(np.diff(p)))
        mu0 = 0.5 * (S[k] + S[k + 1])
        window = np.abs(S - mu0) <= 2.5
        s_w, p_w = S[window], p[window]
        a_steep, _ = lm(lambda q: model_a(q, s_w) - p_w,
                        [p_w[0], 0.0, p_w[-1] - p_w[0], mu0, np.log(0.7), 0.0], [1e-4] * 6,
                        watch=3)
        start = [p[S <= -1].mean(), 0.0, p[S >= 1].mean() - p[S <= -1].mean(), 0.0, np.log(0.7),
                 0.0]
        a_zero, _ = lm(lambda q: model_a(q, S) - p, start, [1e-4] * 6, watch=3)
        b_zero, _ = lm(lambda q: model_b(q, S) - p, start + [0.0, 0.0], [1e-4] * 8, watch=3)
        # B after A on the edge stage's own window (around the steepest descent).
        b_steep, _ = lm(lambda q: model_b(q, s_w) - p_w, list(a_steep) + [0.0, 0.0], [1e-4] * 8,
                        watch=3)
        # B after A on the whole window.
        b_after, _ = lm(lambda q: model_b(q, S) - p, list(a_steep) + [0.0, 0.0], [1e-4] * 8,
                        watch=3)
        results.append((a_steep[3], a_zero[3], b_zero[3], b_steep[3], b_after[3]))
    r = np.array(results)
    r = r[np.all(np.abs(r) < 2.5, axis=1)]
    print(f"{camera} {rim}: {len(r)} lines")
    for i, name in enumerate(["A, steepest", "A from 0", "B from 0", "B after A, A's window",
                              "B after A, whole window"]):
        q10, q90 = np.percentile(r[:, i], [10, 90])
        print(f"  {name:24s} mean {r[:, i].mean():+.3f}  median {np.median(r[:, i]):+.3f}  "
              f"q10 / q90 {q10:+.3f} / {q90:+.3f}  inside 0.4 px {np.mean(r[:, i] < -0.4):.2f}")


if __name__ == "__main__":
    with np.errstate(all="ignore"):
        main()
