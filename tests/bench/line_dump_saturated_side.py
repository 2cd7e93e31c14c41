#!/usr/bin/python3
"""Edge lines of a JPEG render against its PNG twin, by the side a clipped channel is on: the
lines edge_bias_probe --dump writes, matched by camera, frame and centre (compare_line_dumps.py).

Usage: line_dump_saturated_side.py [--clip LEVEL] [--by-rim] PNG.txt JPEG.txt [MORE.txt ...]
Each line is classed on the first file after the reference (the decoded frame, as the edge stage
reads it): "object" when a channel reaches LEVEL (linear; default 0.95, EdgeLineOptions::
clip_level) on the line and its mean over the object's side (s <= -1.5 px) is at least LEVEL
while the background's (s >= +1.5 px) is below; "background" the other way round (when a line
has both, it counts as "object"); "other" when a channel reaches LEVEL otherwise; "none" when no
channel does. Per camera and class: the number of lines found in every file, the reference's mean
μ (px, + = outside the true contour), and for each further file the mean and the mean absolute
value of μ − μ_reference over the same lines; with --by-rim, per camera, rim (the probe's
up / down / left / right bins) and class instead. Not a test.
"""
import argparse
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from compare_line_dumps import load_profiles  # noqa: E402

STEP_PX = 0.25
PLATEAU_PX = 1.5


def saturated_side(profile, clip):
    """The class of one line's linear RGB profile (samples × 3, centred on the contour)."""
    half = len(profile) // 2
    s = (np.arange(len(profile)) - half) * STEP_PX
    inside = profile[s <= -PLATEAU_PX].mean(0)
    outside = profile[s >= PLATEAU_PX].mean(0)
    classes = set()
    for c in range(3):
        if profile[:, c].max() < clip:
            continue
        if inside[c] >= clip > outside[c]:
            classes.add("object")
        elif outside[c] >= clip > inside[c]:
            classes.add("background")
        else:
            classes.add("other")
    for name in ("object", "background", "other"):
        if name in classes:
            return name
    return "none"


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--clip", type=float, default=0.95)
    parser.add_argument("--by-rim", action="store_true")
    parser.add_argument("dumps", nargs="+")
    args = parser.parse_args()
    if len(args.dumps) < 2:
        parser.error("needs a reference and at least one other dump")
    data = [load_profiles(path) for path in args.dumps]
    keys = set(data[0])
    for lines in data[1:]:
        keys &= set(lines)
    groups = {}
    for key in keys:
        kind = saturated_side(data[1][key][2], args.clip)
        mus = [lines[key][1] for lines in data]
        if args.by_rim:
            groups.setdefault((f"{key[0]} {data[0][key][0]}", kind), []).append(mus)
            continue
        for camera in (key[0], "all"):
            groups.setdefault((camera, kind), []).append(mus)
    print(f"{len(keys)} lines found in every file; per file, mean / mean |μ − μ_reference| (px)")
    names = " | ".join(os.path.basename(p) for p in args.dumps[1:])
    print(f"{'camera':10} {'class':10} {'lines':>6} {'reference μ':>12} | {names}")
    for (camera, kind), rows in sorted(groups.items()):
        mus = np.array(rows)
        cells = " | ".join(
            f"{np.mean(mus[:, i] - mus[:, 0]):+.3f} / {np.mean(np.abs(mus[:, i] - mus[:, 0])):.3f}"
            for i in range(1, mus.shape[1]))
        print(f"{camera:10} {kind:10} {len(mus):6d} {np.mean(mus[:, 0]):+12.3f} | {cells}")


if __name__ == "__main__":
    main()
