#!/usr/bin/env python3
"""Robust location of the measured edge per camera and rim bin of `edge_bias_probe --dump` files.

Usage: edge_dump_locations.py DUMP [DUMP ...]
For every camera and normal bin (up, down, left, right) of each dump, prints the plain mean of
the lines' μ (px, + = outside the true contour, the probe runs at the true pose) and the
M-estimate of one common edge offset x under several losses of the normalised residual
r = (x − μ)/σ (σ floored at 0.1 px as in the pose stage): Cauchy 3 (the edge stage's loss),
Tukey 4, and one-sided forms that redescend (Tukey) only for r > 0, i.e. for lines found inside
the contour, and are Cauchy or quadratic for lines found outside. A one-sided loss models an
error process whose outliers lie only inside (docs/notes/issue12_rim_shading.md). Not a test;
numpy.
"""
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


ESTIMATORS = [
    ("cauchy 3", cauchy),
    ("tukey 4", lambda r: tukey(r, 4.0)),
    ("in: tukey 3 / out: cauchy 3", lambda r: np.where(r > 0, tukey(r, 3.0), cauchy(r))),
    ("in: tukey 4 / out: cauchy 3", lambda r: np.where(r > 0, tukey(r, 4.0), cauchy(r))),
    ("in: tukey 3 / out: quadratic", lambda r: np.where(r > 0, tukey(r, 3.0), r)),
]


def main(paths):
    if not paths:
        raise SystemExit(__doc__)
    header = ["dump", "camera", "bin", "lines", "mean"] + [name for name, _ in ESTIMATORS]
    print("| " + " | ".join(header) + " |")
    print("|" + "---|" * len(header))
    for path in paths:
        for (camera, normal_bin), rows in sorted(load(path).items()):
            mu = np.array([row[0] for row in rows])
            sigma = np.array([row[1] for row in rows])
            values = [mu.mean()] + [m_estimate(mu, sigma, psi) for _, psi in ESTIMATORS]
            cells = [path.split("/")[-1], camera, normal_bin, str(len(mu))]
            print("| " + " | ".join(cells + [f"{v:+.3f}" for v in values]) + " |")


if __name__ == "__main__":
    main(sys.argv[1:])
