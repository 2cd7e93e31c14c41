#!/usr/bin/env python3
"""Refits the edge lines of `edge_bias_probe --dump` files with and without a √d rim term.

Usage: edge_rim_sqrt_fit.py [--inside] LINES DUMP [DUMP ...]
LINES lines are drawn at random from each dump (seed 0 for each). For each, the scalar profile is formed
as the edge stage forms it (projection of the linear RGB samples on the contrast direction of
the channels below 0.95, mean over s in [-4, -1] minus mean over [1, 4]) and fitted over
|s - mu0| <= 2.5 px (mu0: the steepest sample within 2 px) by Levenberg-Marquardt with a
numerical Jacobian, two ways:
  M0    a + g(s - mu0) + b Phi(z) + k w (z Phi(z) + phi(z)),  z = (s - mu)/w
        (the edge stage's model, edge_lines.h; its mu should match the probe's);
  sqrt  M0 + c sqrt(w) H(z),  H(z) = integral over u > z of sqrt(u - z) phi(u) du,
        the blurred sqrt(max(0, mu - s)): near an occluding contour the surface normal turns
        as the square root of the distance to it, so a radiance smooth in the normal varies
        as sqrt(d) inside the edge. The grazing-angle sliver is then part of one ramp whose
        shape is fixed, rather than a free offset of the edge.
With --inside the second model is instead
  inside  a + b Phi(z) + g w (z Phi(z) + phi(z)) + c sqrt(w) H(z)
        (no common linear trend: the inside varies as the blurred sqrt only, the outside
        linearly), fitted over every sample from the inside end of the profile to mu0 + 2.5 px,
        so the inside trend is read over 4 px rather than 2.5.
Prints per camera and normal bin (up, down, left, right): the count and the mean and median mu
(px, + = outside the true contour; the probe runs at the true pose) of the probe, M0 and sqrt,
and per camera the difference of the means up - down.
Not a test; numpy only, about 10 ms per line.
"""
import math
import sys

import numpy as np

from edge_profile_refit import (cdf, cdf_integral, edge_model, levenberg_marquardt, print_bins,
                                scalar_profile, start)

U = np.linspace(-8.0, 8.0, 4001)
GAUSS = np.exp(-U**2 / 2.0) / math.sqrt(2.0 * math.pi)
Z_GRID = np.linspace(-12.0, 12.0, 2401)
H_GRID = np.array([np.sum(np.sqrt(np.maximum(0.0, U - z)) * GAUSS) * (U[1] - U[0]) for z in Z_GRID])


def blurred_sqrt(z):
    return np.where(z < Z_GRID[0], np.sqrt(np.maximum(-z, 0.0)), np.interp(z, Z_GRID, H_GRID))


def model(p, s, mu0, with_sqrt):
    w = math.exp(p[4])
    if with_sqrt == "inside":
        a, g, b, mu, _, k = p[:6]
        z = (s - mu) / w
        return a + b * cdf(z) + g * w * cdf_integral(z) + k * math.sqrt(w) * blurred_sqrt(z)
    value = edge_model(p, s, mu0)
    if with_sqrt:
        value = value + p[6] * math.sqrt(w) * blurred_sqrt((s - p[3]) / w)
    return value


def fit(s, y, mu0, with_sqrt):
    """The parameters, or None when mu or w leave their plausible range."""
    p = start(s, y, mu0, 1 if with_sqrt is True else 0)
    return levenberg_marquardt(lambda q, x: model(q, x, mu0, with_sqrt), p, s, y, mu0)


def run(path, max_lines, inside_model):
    rng = np.random.default_rng(0)
    rows = [line.split() for line in open(path)]
    half = (len(rows[0]) - 9) // 3 // 2
    s = np.arange(-half, half + 1) * 0.25
    results = {}
    for i in rng.permutation(len(rows))[:max_lines]:
        fields = rows[i]
        colors = np.array(fields[9:], float).reshape(-1, 3)
        profile = scalar_profile(colors, s)
        if profile is None:
            continue
        y, mu0 = profile
        window = np.abs(s - mu0) <= 2.5
        plain = fit(s[window], y[window], mu0, False)
        if inside_model:
            wide = s - mu0 <= 2.5
            rim = fit(s[wide], y[wide], mu0, "inside")
        else:
            rim = fit(s[window], y[window], mu0, True)
        if plain is None or rim is None:
            continue
        results.setdefault((fields[0], fields[2]), []).append((float(fields[7]), plain[3], rim[3]))
    print_bins(path, results, ("probe", "M0", "inside" if inside_model else "sqrt"))


def main():
    args = sys.argv[1:]
    inside = bool(args) and args[0] == "--inside"
    if inside:
        args = args[1:]
    if len(args) < 2:
        sys.exit(__doc__)
    for path in args[1:]:
        run(path, int(args[0]), inside)


if __name__ == "__main__":
    main()
