#!/usr/bin/python3
"""How far each edge line's image edge moves when the pose it is measured from moves.

Usage: /usr/bin/python3 tests/bench/edge_stiffness.py TRUTH.txt MOVED.txt [--white W]
                                                      [--window-px P]

TRUTH.txt and MOVED.txt are `edge_bias_probe --dump` files of one sequence, measured at the
ground truth and at moved poses (`--at`, e.g. from tests/bench/move_poses.py). Each line of
TRUTH is paired with the nearest line of MOVED in the same camera and frame (centres within
1 px, normals within 25°). The image edge a line finds lies at centre + μ·n; a line that
measures a fixed image edge finds it at the same place from both poses, a "soft" one moves it
with the pose. Prints per camera, rim and background (white-ish: every channel's mean linear
value over 1.25–4 px outside the true contour above W, default 0.35; else coloured) the number
of pairs, the mean μ at the truth (px) and the mean move of the edge along n (px, 0 = stiff).
docs/notes/issue12_bias_attribution.md, "Which lines are soft". Not a test.
"""
import argparse
from collections import defaultdict

import numpy as np


def load(path, window_px):
    """(camera, frame) -> list of (rim, centre, normal, μ, outside colour)."""
    lines = defaultdict(list)
    with open(path) as f:
        for row in f:
            fields = row.split()
            if "BLUR" in fields:  # --blur-exposure appends the contour crossings
                fields = fields[: fields.index("BLUR")]
            values = np.array([float(v) for v in fields[3:9]])
            profile = np.array([float(v) for v in fields[9:]]).reshape(-1, 3)
            half = profile.shape[0] // 2  # samples at k·window_px/half, k = −half..half
            first_outside = half + int(np.ceil(1.25 * half / window_px))
            outside = profile[first_outside:].mean(axis=0)
            lines[(fields[0], int(fields[1]))].append(
                (fields[2], values[0:2], values[2:4], values[4], outside))
    return lines


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("truth")
    parser.add_argument("moved")
    parser.add_argument("--white", type=float, default=0.35)
    parser.add_argument("--window-px", type=float, default=4.0,
                        help="the probe's edge.window_px (the dumps' profile half-length)")
    args = parser.parse_args()
    truth, moved = load(args.truth, args.window_px), load(args.moved, args.window_px)
    groups = defaultdict(list)
    for key, lines in truth.items():
        others = moved.get(key, [])
        if not others:
            continue
        centres = np.array([other[1] for other in others])
        for rim, centre, normal, mu, outside in lines:
            distance = np.linalg.norm(centres - centre, axis=1)
            j = int(np.argmin(distance))
            if distance[j] > 1.0 or np.dot(others[j][2], normal) < np.cos(np.radians(25)):
                continue
            edge_truth = centre + mu * normal
            edge_moved = others[j][1] + others[j][3] * normal
            white = outside.min() > args.white
            groups[(key[0], rim, white)].append((mu, float(np.dot(edge_moved - edge_truth, normal))))
    print(f"{'camera':6} {'rim':5} {'background':10} {'pairs':>6} {'mean μ':>8} {'edge move':>9}")
    for (camera, rim, white), values in sorted(groups.items()):
        values = np.array(values)
        print(f"{camera:6} {rim:5} {'white-ish' if white else 'coloured':10} {len(values):6d} "
              f"{values[:, 0].mean():+8.3f} {values[:, 1].mean():+9.3f}")


if __name__ == "__main__":
    main()
