#!/usr/bin/python3
"""Does a rim radiance shared by a camera's whole sequence explain the edge offsets at the true
pose (docs/notes/issue12_occlusion_contours.md, "A shared rim radiance")?

Reads an `edge_bias_probe --dump` file (lines measured at the true pose) and fits, per camera,
by iteratively reweighted least squares (Cauchy weights at 3 sigma, sigma = the line's),

  pose only:   mu_i = n_i . t_f + s_f n_i . q_i + r_f n_i x q_i
  with rim:    ... + sum_{c,m} beta_cm d_ic f_m(theta_i) / b_i + gamma (A_i . d_i) / b_i

t_f, s_f, r_f: a 2-D similarity per frame (shift in px, scale and in-plane rotation about the
lines' centroid, q in units of 100 px); theta_i the normal's angle; f_m its Fourier basis up to
order M; d_i the line's unit contrast direction (unclipped channels), b_i its contrast, A_i its
inside colour. A sliver of rim radiance rho(theta) next to the edge moves the fitted step centre
by about w (rho - A).d / b: a shared rho(theta) explains the offsets if the frames' shifts t_f
then average to zero. Prints their means (px) per camera for both models.

Usage: tests/bench/edge_rim_radiance_fit.py DUMP [M, default 3]. Not a test.
"""
import sys

import numpy as np

S = (np.arange(33) - 16) * 0.25  # the probe's samples: -4 ... +4 px every 0.25 px


def read_lines(path):
    rows = []
    for text in open(path):
        t = text.split()
        colors = np.array(t[9:9 + 99], float).reshape(33, 3)
        inside = colors[(S >= -4) & (S <= -1)].mean(0)
        outside = colors[(S >= 1) & (S <= 4)].mean(0)
        d = (inside - outside) * (colors.max(0) < 0.95)
        b = np.linalg.norm(d)
        if b < 0.02:
            continue
        d /= b
        cx, cy, nx, ny, mu, sigma = map(float, t[3:9])
        rows.append((t[0], int(t[1]), cx, cy, nx, ny, mu, max(sigma, 0.1), *d, inside @ d, b))
    return rows


def irls(x, mu, sigma):
    w = 1.0 / sigma**2
    beta = np.zeros(x.shape[1])
    for _ in range(15):
        xw = x * w[:, None]
        beta = np.linalg.lstsq(xw.T @ x + 1e-9 * np.eye(x.shape[1]), xw.T @ mu, rcond=None)[0]
        r = (mu - x @ beta) / sigma
        w = 1.0 / sigma**2 / (1 + (r / 3.0)**2)
    return beta, mu - x @ beta


def main():
    rows = read_lines(sys.argv[1])
    order = int(sys.argv[2]) if len(sys.argv) > 2 else 3
    for cam in sorted(set(r[0] for r in rows)):
        c = np.array([r[1:] for r in rows if r[0] == cam], float)
        frame, p, n, mu, sigma = c[:, 0].astype(int), c[:, 1:3], c[:, 3:5], c[:, 5], c[:, 6]
        d, inside_d, b = c[:, 7:10], c[:, 10], c[:, 11]
        frames = sorted(set(frame))
        index = np.searchsorted(frames, frame)
        pose = np.zeros((len(c), 4 * len(frames)))
        for k in range(len(frames)):
            m = index == k
            q = (p[m] - p[m].mean(0)) / 100.0
            pose[m, 4 * k:4 * k + 4] = np.column_stack(
                [n[m, 0], n[m, 1], (n[m] * q).sum(1), n[m, 1] * q[:, 0] - n[m, 0] * q[:, 1]])
        theta = np.arctan2(n[:, 1], n[:, 0])
        basis = [np.ones_like(theta)] + [g(k * theta) for k in range(1, order + 1)
                                         for g in (np.cos, np.sin)]
        rim = np.column_stack([d[:, ch] * f / b for ch in range(3) for f in basis] +
                              [inside_d / b])
        print(f"{cam}: {len(c)} lines, {len(frames)} frames")
        for name, x in (("pose only", pose), (f"with rim, M = {order}", np.hstack([pose, rim]))):
            beta, residual = irls(x, mu, sigma)
            per_frame = beta[:4 * len(frames)].reshape(-1, 4)
            print(f"  {name:16s} shift x {per_frame[:, 0].mean():+.3f} y {per_frame[:, 1].mean():+.3f}"
                  f"  scale {per_frame[:, 2].mean():+.3f}  median |residual| "
                  f"{np.median(np.abs(residual)):.3f}")


if __name__ == "__main__":
    main()
