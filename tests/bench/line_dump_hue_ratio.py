#!/usr/bin/python3
"""Would the body's hue predict how far above full scale a clipped channel is? On an
edge_bias_probe --dump of a lossless render (e.g. a PNG twin): the ratio of channel C to channel
O on the object's plateau (s <= -1.5 px) of lines where nothing clips and C stays below 0.9, per
camera and rim; and, for the lines whose C is clipped on the object's side only
(line_dump_saturated_side.py's "object" class), the median O plateau per camera and rim times the
camera's median ratio: the level a body of constant hue would have there (full scales).

Usage: line_dump_hue_ratio.py DUMP.txt [C O]   (channels 0 = R, 1 = G, 2 = B; default 0 1)
Not a test.
"""
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from compare_line_dumps import load_profiles  # noqa: E402
from line_dump_saturated_side import PLATEAU_PX, STEP_PX, saturated_side  # noqa: E402


def main():
    if len(sys.argv) not in (2, 4):
        sys.exit(__doc__)
    lines = load_profiles(sys.argv[1])
    c, o = (int(sys.argv[2]), int(sys.argv[3])) if len(sys.argv) == 4 else (0, 1)
    ratios, levels = {}, {}
    for key, (rim, _, profile) in lines.items():
        s = (np.arange(len(profile)) - len(profile) // 2) * STEP_PX
        inside = profile[s <= -PLATEAU_PX].mean(0)
        kind = saturated_side(profile, 0.95)
        if kind == "none" and profile[:, c].max() < 0.9:
            ratio = inside[c] / max(inside[o], 1e-3)
            ratios.setdefault(key[0], []).append(ratio)
            ratios.setdefault((key[0], rim), []).append(ratio)
        elif kind == "object":
            levels.setdefault((key[0], rim), []).append(inside[o])
    for key in sorted(ratios, key=str):
        q = np.quantile(ratios[key], [0.25, 0.5, 0.75])
        print(f"unclipped {str(key):20} {len(ratios[key]):5d} lines, ratio quartiles "
              f"{q[0]:.2f} {q[1]:.2f} {q[2]:.2f}")
    for key in sorted(levels):
        if key[0] not in ratios:
            continue
        level = np.median(levels[key]) * np.median(ratios[key[0]])
        print(f"clipped   {str(key):20} {len(levels[key]):5d} lines, median plateau of channel "
              f"{o} {np.median(levels[key]):.3f} -> level {level:.2f}")


if __name__ == "__main__":
    main()
