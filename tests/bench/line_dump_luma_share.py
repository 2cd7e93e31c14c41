#!/usr/bin/python3
"""Per-line offsets of two twins of one render against a reference twin, grouped by how much of
each line's contrast is luma: edge_bias_probe --dump files, lines matched by camera, frame and
centre (as compare_line_dumps.py matches them).

Usage: line_dump_luma_share.py REFERENCE.txt A.txt B.txt
A line's luma share is |ΔY| / |ΔRGB| of the reference profile (linear light, Rec. 709 luma; the
mean of its outer quarter minus that of its inner quarter): 0 for two colours of equal
luma (a hue edge), 0.58 for a grey step, more for a step mostly in green. Prints, per group, the
number of lines and the mean |μ − μ_reference| (px) of A and of B. Not a test.
"""
import sys

import os

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from compare_line_dumps import load_profiles  # noqa: E402

LUMA = np.array([0.2126, 0.7152, 0.0722])


def main():
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    reference, a, b = (load_profiles(path) for path in sys.argv[1:])
    keys = [k for k in reference if k in a and k in b]
    share, da, db = [], [], []
    for k in keys:
        profile = reference[k][2]
        quarter = max(1, len(profile) // 4)
        step = profile[-quarter:].mean(0) - profile[:quarter].mean(0)
        share.append(abs(step @ LUMA) / max(np.linalg.norm(step), 1e-9))
        da.append(abs(a[k][1] - reference[k][1]))
        db.append(abs(b[k][1] - reference[k][1]))
    share, da, db = map(np.array, (share, da, db))
    print(f"| luma share | lines | mean |Δμ| {sys.argv[2]} | mean |Δμ| {sys.argv[3]} |")
    print("|---|---:|---:|---:|")
    for lo, hi in [(0.0, 0.2), (0.2, 0.4), (0.4, 0.6), (0.6, 2.0)]:
        m = (share >= lo) & (share < hi)
        print(f"| {lo:.1f}–{hi:.1f} | {m.sum()} | {da[m].mean():.3f} | {db[m].mean():.3f} |")
    print(f"| all | {len(keys)} | {da.mean():.3f} | {db.mean():.3f} |")


if __name__ == "__main__":
    main()
