#!/usr/bin/env python3
"""Robust location of the measured edge per camera and rim bin of `edge_bias_probe --dump` files.

Usage: [BCOT_MIXTURE_REACH_PX=R] [BCOT_MIXTURE_SUPPORT=edge|window] edge_dump_locations.py DUMP ...
For every camera and normal bin (up, down, left, right) of each dump, prints the plain mean of
the lines' μ (px, + = outside the true contour, the probe runs at the true pose) and the
M-estimate of one common edge offset x under several losses of the normalised residual
r = (x − μ)/σ (σ floored at 0.1 px as in the pose stage): Cauchy 3 (the edge stage's loss),
Tukey 4, and one-sided forms that redescend (Tukey) only for r > 0, i.e. for lines found inside
the contour, and are Cauchy or quadratic for lines found outside. A one-sided loss models an
error process whose outliers lie only inside (docs/notes/issue12_rim_shading.md).
The last two columns are maximum-likelihood offsets under a mixture model of the lines (see
mixture()), without and with a part for lines found inside the edge
(docs/notes/issue12_inward_mixture.md). Its uniform parts span R px (default 2, the edge stage's
search_px) around the fitted offset (`edge`, the default) or the search window [−R, R] around the
line's anchor (`window`). After the bins, the mean |offset|, mean offset and largest |offset| of
each column over all bins. Not a test; numpy.
"""
import os
import sys

import numpy as np

CAUCHY_SCALE = 3.0


def load(path):
    bins = {}
    with open(path) as dump:
        for line in dump:
            fields = line.split()
            bins.setdefault((fields[0], fields[2]), []).append(
                (float(fields[7]), max(float(fields[8]), 0.1)))
    return bins


def cauchy(r):
    return r / (1.0 + (r / CAUCHY_SCALE) ** 2)


def tukey(r, k):
    return np.where(np.abs(r) < k, r * (1.0 - (r / k) ** 2) ** 2, 0.0)


def m_estimate(mu, sigma, psi, iterations=100):
    """Iteratively reweighted mean of μ with the weights ψ(r)/r, from the median."""
    x = np.median(mu)
    for _ in range(iterations):
        r = (x - mu) / sigma
        safe = np.where(np.abs(r) < 1e-9, 1.0, r)
        w = np.where(np.abs(r) < 1e-9, 1.0, psi(safe) / safe)
        if np.sum(w / sigma**2) <= 0.0:
            return float("nan")
        x = np.sum(w * mu / sigma**2) / np.sum(w / sigma**2)
    return x


def mixture_em(mu, sigma, x, inward_part, reach, window_support, iterations=200):
    """EM of mixture() from offset x; returns (x, log-likelihood)."""
    scale, pi_o, pi_t = 1.0, 0.1, (0.1 if inward_part else 0.0)
    for _ in range(iterations):
        r = (mu - x) / (scale * sigma)
        edge = (1.0 - pi_o - pi_t) * np.exp(-0.5 * r**2) / (np.sqrt(2.0 * np.pi) * scale * sigma)
        if window_support:
            anywhere = np.where(np.abs(mu) <= reach, pi_o / (2.0 * reach), 0.0)
            inward = np.where((mu <= x) & (mu >= -reach), pi_t / max(x + reach, 1e-3), 0.0)
        else:
            anywhere = np.where(np.abs(mu - x) <= reach, pi_o / (2.0 * reach), 0.0)
            inward = np.where((mu <= x) & (mu >= x - reach), pi_t / reach, 0.0)
        total = edge + anywhere + inward + 1e-300
        w_edge, w_any, w_in = edge / total, anywhere / total, inward / total
        x = np.sum(w_edge * mu / sigma**2) / np.sum(w_edge / sigma**2)
        scale = max(np.sqrt(np.sum(w_edge * ((mu - x) / sigma) ** 2) / np.sum(w_edge)), 1e-3)
        pi_o, pi_t = w_any.mean(), w_in.mean()
    return x, np.sum(np.log(total))


def mixture(mu, sigma, inward_part, reach, window_support):
    """Maximum-likelihood offset x under a three-part model of the lines' μ: the edge,
    N(x, (s·σ_i)²) with one common scale s; lines found anywhere, uniform (weight π_o); and, if
    `inward_part`, lines found inside the edge, uniform (weight π_t: the rims whose outer sliver
    looks like the background). The uniform parts span [x − reach, x + reach] and
    [x − reach, x], or with `window_support` [−reach, reach] and [−reach, x]. EM from the 10th
    to the 90th percentile of μ; the start of the largest likelihood wins."""
    fits = [mixture_em(mu, sigma, np.percentile(mu, q), inward_part, reach, window_support)
            for q in range(10, 100, 10)]
    return max(fits, key=lambda fit: fit[1])[0]


ESTIMATORS = [
    ("cauchy 3", cauchy),
    ("tukey 4", lambda r: tukey(r, 4.0)),
    ("tukey 7", lambda r: tukey(r, 7.0)),
    ("in: tukey 3 / out: cauchy 3", lambda r: np.where(r > 0, tukey(r, 3.0), cauchy(r))),
    ("in: tukey 4 / out: cauchy 3", lambda r: np.where(r > 0, tukey(r, 4.0), cauchy(r))),
    ("in: tukey 3 / out: quadratic", lambda r: np.where(r > 0, tukey(r, 3.0), r)),
]
MIXTURES = [("mixture", False), ("mixture + inward", True)]


def main(paths):
    if not paths:
        raise SystemExit(__doc__)
    reach = float(os.environ.get("BCOT_MIXTURE_REACH_PX", "2"))
    support = os.environ.get("BCOT_MIXTURE_SUPPORT", "edge")
    if support not in ("edge", "window") or not reach > 0.0:
        raise SystemExit("BCOT_MIXTURE_SUPPORT must be edge or window, BCOT_MIXTURE_REACH_PX > 0")
    header = ["dump", "camera", "bin", "lines", "mean"] + [name for name, _ in ESTIMATORS + MIXTURES]
    print("| " + " | ".join(header) + " |")
    print("|" + "---|" * len(header))
    table = []
    for path in paths:
        for (camera, normal_bin), rows in sorted(load(path).items()):
            mu = np.array([row[0] for row in rows])
            sigma = np.array([row[1] for row in rows])
            values = ([mu.mean()] + [m_estimate(mu, sigma, psi) for _, psi in ESTIMATORS] +
                      [mixture(mu, sigma, inward, reach, support == "window") for _, inward in MIXTURES])
            table.append(values)
            cells = [path.split("/")[-1], camera, normal_bin, str(len(mu))]
            print("| " + " | ".join(cells + [f"{v:+.3f}" for v in values]) + " |")
    table = np.array(table)
    for name, column in [("mean |offset|", np.abs(table).mean(axis=0)),
                         ("mean offset", table.mean(axis=0)),
                         ("largest |offset|", np.abs(table).max(axis=0))]:
        print("| " + " | ".join([f"**{name}**", "", "", ""] + [f"{v:+.3f}" for v in column]) + " |")


if __name__ == "__main__":
    main(sys.argv[1:])
