#!/usr/bin/env python3
"""Refits the edge lines of `edge_bias_probe --dump` files with and without a Fresnel rim term.

Usage: edge_rim_fresnel_fit.py [--exponent E] LINES DUMP [DUMP ...]
The dumps must carry the per-sample normals (`NVS` columns) that the probe of
docs/notes/patches/issue12_rim_shading.patch writes: at every profile sample inside the true
contour, the cosine n·v of the mesh's interpolated (smooth) normal with the viewing ray.
LINES lines are drawn at random from each dump (seed 0). The scalar profile is formed as in
edge_rim_sqrt_fit.py and fitted over |s - mu0| <= 2.5 px two ways:
  M0    the edge stage's blurred step with linear trends (edge_lines.h);
  rim   M0 + c G(s), G = the blur (width w, the fit's own) of f(u - mu) for u inside, with
        f = (1 - n.v)^E at the samples: the shape a grazing-angle term takes (Schlick's Fresnel
        factor, and the retro-reflection factor of a rough diffuse surface, both vary as
        (1 - n.v)^5), moved with the fitted edge. Its shape comes from the mesh, only its
        amplitude c from the profile.
Prints per camera and normal bin the mean and median mu (px, + = outside the true contour) of
the probe, M0 and rim, and per camera the difference up - down. Not a test; numpy only.
"""
import argparse
import math

import numpy as np

from edge_profile_refit import (S, SAMPLES, cdf, edge_model, levenberg_marquardt, print_bins,
                                scalar_profile, start)

def model(p, s, mu0, rim):
    value = edge_model(p, s, mu0)
    if rim is not None:
        # Sample u covers [u - 1/8, min(u + 1/8, 0)] of the rim; moved by mu and blurred, the
        # indicator of [lo, hi] is Phi((s - lo)/w) - Phi((s - hi)/w).
        centres, shape = rim
        mu, w = p[3], math.exp(p[4])
        lo = centres - 0.125 + mu
        hi = np.minimum(centres + 0.125, 0.0) + mu
        blurred = cdf((s[:, None] - lo[None, :]) / w) - cdf((s[:, None] - hi[None, :]) / w)
        value = value + p[6] * (blurred * shape[None, :]).sum(1)
    return value


def fit(s, y, mu0, rim):
    """The parameters, or None when mu or w leave their plausible range."""
    p = start(s, y, mu0, 1 if rim else 0)
    return levenberg_marquardt(lambda q, x: model(q, x, mu0, rim), p, s, y, mu0)


def run(path, max_lines, exponent):
    rng = np.random.default_rng(0)
    rows = [line.split() for line in open(path)]
    results = {}
    for i in rng.permutation(len(rows))[:max_lines]:
        fields = rows[i]
        colors = np.array(fields[9:9 + 3 * SAMPLES], float).reshape(-1, 3)
        first = fields.index("NVS") + 1
        nv = np.array(fields[first:first + 2 * SAMPLES], float).reshape(-1, 2)[:, 0]
        profile = scalar_profile(colors, S)
        if profile is None:
            continue
        y, mu0 = profile
        window = np.abs(S - mu0) <= 2.5
        hit = (nv > -1.0) & (S <= 0.0)
        rim_shape = (S[hit], (1.0 - np.clip(nv[hit], 0.0, 1.0)) ** exponent)
        plain = fit(S[window], y[window], mu0, None)
        rim = fit(S[window], y[window], mu0, rim_shape)
        if plain is None or rim is None:
            continue
        results.setdefault((fields[0], fields[2]), []).append((float(fields[7]), plain[3], rim[3]))
    print_bins(path, results, ("probe", "M0", "rim"))


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--exponent", type=float, default=5.0, help="of (1 - n.v)")
    parser.add_argument("lines", type=int, help="lines drawn from each dump")
    parser.add_argument("dumps", nargs="+")
    args = parser.parse_args()
    for path in args.dumps:
        run(path, args.lines, args.exponent)


if __name__ == "__main__":
    main()
