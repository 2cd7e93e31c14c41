#!/usr/bin/env python3
"""How motion blur spreads the edge lines, and a refit with a ramp (box-blurred) step model.

Usage: edge_blur_refit.py [--psf W0] LINES DUMP [DUMP ...]
       edge_blur_refit.py --probe-only DUMP [DUMP ...]
DUMP: `edge_bias_probe --sequence SEQ --config configs/annotate.yaml --dump DUMP
--blur-exposure E` (E = the exposure in frames), whose lines end with the true contour's
crossings of the line at 8 times over the exposure. The smear of a line is the distance its
contour crossing moves over the exposure: a contour moving along the line's normal by L px
turns the blurred step into a ramp of length L. LINES lines are drawn at random (seed 0) and
fitted two ways, with the profile formed as in edge_rim_sqrt_fit.py:
  M0    the edge stage's model over |s - mu0| <= 2.5 px: a + g u + b Phi(z) + k w R(z);
  ramp  the same trends with a step blurred by a box of length L and a Gaussian of width W0
        (the lens and pixel; default 0.6 px), over |s - mu0| <= 4 px; its width parameter is
        the total sigma(L) = sqrt(W0^2 + L^2/12), so L = 0 is M0 with w = W0.
Prints per smear class the count and the mean, median and interquartile range of mu (px, + =
outside the true contour) of the probe, M0 and ramp. --probe-only: no refits; per smear class
(finer) over every line, the probe's mu and the median of its sigma (floored as the edge stage
floors it). Not a test; numpy only.
"""
import argparse
import math

import numpy as np

from edge_profile_refit import (S, SAMPLES, cdf, cdf_integral, edge_model, levenberg_marquardt,
                                scalar_profile, start)

SMEAR_CLASSES = ((0.0, 0.5), (0.5, 1.0), (1.0, 2.0), (2.0, 99.0))


def ramp(p, s, mu0, psf):
    a, g, b, mu, log_sigma, k = p
    box = math.sqrt(12.0 * max(math.exp(2.0 * log_sigma) - psf * psf, 0.0))
    z = (s - mu) / psf
    if box < 1e-6:
        step = cdf(z)
    else:  # the mean of Phi((s - mu - x)/W0) over x in [-L/2, L/2]
        step = (cdf_integral(z + 0.5 * box / psf) - cdf_integral(z - 0.5 * box / psf)) * psf / box
    return a + g * (s - mu0) + b * step + k * psf * cdf_integral(z)


def smear(fields):
    """How far the true contour's crossing of a dump line moves over the exposure (px), or None
    when the line has no finite crossings."""
    if "BLUR" not in fields:
        return None
    crossings = np.array(fields[fields.index("BLUR") + 1:], float)
    return abs(crossings[-1] - crossings[0]) if np.all(np.isfinite(crossings)) else None


def run(path, max_lines, psf):
    rng = np.random.default_rng(0)
    rows = [line.split() for line in open(path)]
    results = []
    for i in rng.permutation(len(rows))[:max_lines]:
        fields = rows[i]
        line_smear = smear(fields)
        if line_smear is None:
            continue
        profile = scalar_profile(np.array(fields[9:9 + 3 * SAMPLES], float).reshape(-1, 3), S)
        if profile is None:
            continue
        y, mu0 = profile
        near, wide = np.abs(S - mu0) <= 2.5, np.abs(S - mu0) <= 4.0
        plain = levenberg_marquardt(lambda q, x: edge_model(q, x, mu0),
                                    start(S[near], y[near], mu0, 0), S[near], y[near], mu0)
        blurred = levenberg_marquardt(lambda q, x: ramp(q, x, mu0, psf),
                                      start(S[wide], y[wide], mu0, 0), S[wide], y[wide], mu0)
        results.append((line_smear, float(fields[7]),
                        plain[3] if plain is not None else np.nan,
                        blurred[3] if blurred is not None else np.nan))
    r = np.array(results)
    for low, high in SMEAR_CLASSES:
        members = r[(r[:, 0] >= low) & (r[:, 0] < high)]
        text = f"{path} smear [{low:g}, {high:g}) px n {len(members):4d}"
        for column, name in ((1, "probe"), (2, "M0"), (3, "ramp")):
            mu = members[:, column]
            mu = mu[np.isfinite(mu)]
            if len(mu) == 0:
                continue
            q25, q50, q75 = np.percentile(mu, [25, 50, 75])
            text += (f" | {name} n {len(mu)} mean {mu.mean():+.3f} median {q50:+.3f}"
                     f" IQR {q75 - q25:.3f}")
        print(text)


def probe_only(path):
    classes = ((0.0, 0.25), (0.25, 0.5), (0.5, 1.0), (1.0, 2.0), (2.0, 4.0), (4.0, 99.0))
    rows = []
    for line in open(path):
        fields = line.split()
        line_smear = smear(fields)
        if line_smear is not None:
            rows.append((line_smear, float(fields[7]), float(fields[8])))
    r = np.array(rows)
    for low, high in classes:
        members = r[(r[:, 0] >= low) & (r[:, 0] < high)]
        if len(members) == 0:
            continue
        q25, q75 = np.percentile(members[:, 1], [25, 75])
        print(f"{path} smear [{low:g}, {high:g}) px n {len(members):5d} mean mu "
              f"{members[:, 1].mean():+.3f} IQR {q75 - q25:.3f} median sigma "
              f"{np.median(members[:, 2]):.3f}")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--psf", type=float, default=0.6, help="W0, px")
    parser.add_argument("--probe-only", action="store_true",
                        help="no refits: the probe's mu of every line by smear")
    parser.add_argument("arguments", nargs="+", metavar="[LINES] DUMP")
    args = parser.parse_args()
    if args.probe_only:
        for path in args.arguments:
            probe_only(path)
    else:
        for path in args.arguments[1:]:
            run(path, int(args.arguments[0]), args.psf)


if __name__ == "__main__":
    main()
