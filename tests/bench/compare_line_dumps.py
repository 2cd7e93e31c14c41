#!/usr/bin/python3
"""Compares edge lines measured at the true pose on twins of one render (e.g. its PNG and its
JPEG frames): the --dump files of edge_bias_probe, matched by camera, frame and line centre.

Usage: compare_line_dumps.py REFERENCE.txt OTHER.txt [MORE.txt ...]
Prints per camera and rim (up / down / left / right, the probe's bins) the number of lines
measured in every file, each file's mean μ (px, + = outside the true contour) and, for each
file after the first, the mean |μ − μ_reference| over the same lines. Not a test.
"""
import sys

import numpy as np


def line_key(fields):
    """A dump line's identity across twins: camera, frame and centre."""
    return (fields[0], int(fields[1]), round(float(fields[3]), 2), round(float(fields[4]), 2))


def load_profiles(path):
    """Each dump line's rim, μ and linear RGB profile (samples × 3), by line_key."""
    lines = {}
    with open(path) as f:
        for row in f:
            fields = row.split()
            end = fields.index("BLUR") if "BLUR" in fields else len(fields)
            profile = np.array([float(v) for v in fields[9:end]]).reshape(-1, 3)
            lines[line_key(fields)] = (fields[2], float(fields[7]), profile)
    return lines


def load(path):
    lines = {}
    with open(path) as f:
        for row in f:
            fields = row.split()
            lines[line_key(fields)] = (fields[2], float(fields[7]))
    return lines


def main():
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    dumps = [load(path) for path in sys.argv[1:]]
    names = [path.rsplit("/", 1)[-1] for path in sys.argv[1:]]
    cameras = sorted({key[0] for key in dumps[0]})
    print("| camera | rim | lines | " + " | ".join(f"mean μ {n}" for n in names) + " | " +
          " | ".join(f"mean \\|Δμ\\| {n}" for n in names[1:]) + " |")
    for camera in cameras:
        for rim in ["up", "down", "left", "right"]:
            keys = [k for k in dumps[0] if k[0] == camera and dumps[0][k][0] == rim and
                    all(k in d for d in dumps[1:])]
            if not keys:
                continue
            mu = [np.array([d[k][1] for k in keys]) for d in dumps]
            means = " | ".join(f"{m.mean():+.3f}" for m in mu)
            deltas = " | ".join(f"{np.abs(m - mu[0]).mean():.3f}" for m in mu[1:])
            print(f"| {camera} | {rim} | {len(keys)} | {means} | {deltas} |")


if __name__ == "__main__":
    main()
