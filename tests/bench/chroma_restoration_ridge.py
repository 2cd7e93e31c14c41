#!/usr/bin/python3
"""What the chroma restoration's ridge does to a clean two-colour edge (docs/notes/
issue12_jpeg_chroma.md, "The restoration moved into the edge stage"): the edge of
EdgeImageOfTest (dark blue inside, green outside, linear BGR; 20° from the columns, Gaussian blur
0.7 px, sRGB codes), its chroma through the codec's 4:2:0 path (no quantisation), restored by
chroma_luma_guided.py's polynomial (radius 3, degree 3, misfit floor 0.1, without the isophote
averaging and the hue-slope blend) at each ridge given, in luma codes².

Usage: /usr/bin/python3 tests/bench/chroma_restoration_ridge.py [RIDGE ...]   (default 4 1 0.1 0.01)
Prints the mean error of the restored Cb against the lossless Cb (codes) per 0.5 px of signed
distance from the edge (+ = outside), the decoded Cb's beside it. Not a test.
"""
import math
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..",
                                "scripts", "pbr"))
import jpeg_variants as jv  # noqa: E402
import pbr_common as pc  # noqa: E402
from chroma_luma_guided import fit_planes  # noqa: E402


def main():
    ridges = [float(v) for v in sys.argv[1:]] or [4.0, 1.0, 0.1, 0.01]
    inside, outside = np.array([0.25, 0.05, 0.01]), np.array([0.05, 0.3, 0.08])
    angle = math.radians(20.0)
    rows, cols = np.mgrid[0:96, 0:96]
    distance = (cols - 48.25) * math.cos(angle) + (rows - 48.125) * math.sin(angle)
    outside_share = 0.5 * (1.0 + np.vectorize(math.erf)(distance / (0.7 * math.sqrt(2.0))))
    linear = inside + (outside - inside) * outside_share[..., None]
    y, cb, cr = jv.to_ycbcr(np.round(255.0 * pc.srgb_encode(linear)))
    decoded_cb, decoded_cr = jv.subsample(cb), jv.subsample(cr)
    interior = (cols > 8) & (cols < 88) & (rows > 8) & (rows < 88)
    bins = np.arange(-2.0, 2.0, 0.5)
    print("| distance (px) | decoded Cb error | " +
          " | ".join(f"restored, ridge {r:g}" for r in ridges) + " |")
    print("|---|---:|" + "---:|" * len(ridges))
    restored = []
    for ridge in ridges:
        features, a, b, _ = fit_planes(y, (decoded_cb, decoded_cr), 3, ridge, 3, 0.1)[0]
        restored.append(sum(a_k * f_k for a_k, f_k in zip(a, features)) + b)
    for low in bins:
        mask = interior & (distance >= low) & (distance < low + 0.5)
        cells = [f"{(plane - cb)[mask].mean():+.2f}" for plane in [decoded_cb] + restored]
        print(f"| {low:+.1f} … {low + 0.5:+.1f} | " + " | ".join(cells) + " |")


if __name__ == "__main__":
    main()
