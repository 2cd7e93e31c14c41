#!/usr/bin/python3
"""Edge lines with and without a clipped channel, and what a luminance projection makes of them,
on twins of one render (e.g. its PNG and its 4:2:0 frames): edge_bias_probe --dump files, lines
matched by camera, frame and centre (as compare_line_dumps.py matches them).

Usage: line_dump_clipping.py [--clip LEVEL] [--max-lines N] REFERENCE.txt OTHER.txt [MORE.txt ...]
A line is "clipped" when a channel of the reference's profile reaches LEVEL (linear; default 0.95,
EdgeLineOptions::clip_level; the probe samples bilinearly, so this sees a little less than the
edge stage's per-pixel peak). Per camera and rim, for the clipped and the unclipped lines: their
number and each file's mean μ of the probe (px, + = outside the true contour); then, on up to N
(default 400) of them, each file's mean μ of a simple fit of a blurred step, c0 + c1·Φ((s − μ)/w)
over |s| <= 2.5 px (μ and w on a grid, c0, c1 by least squares), to two projections of the
profile:
  luminance      Rec. 709 luminance of all three channels (linear light);
  unclipped      the same weights with the channels the reference clips left out, as the edge
                 stage leaves clipped channels out of its contrast direction.
Under 4:2:0 chroma each channel carries the chroma's blur; the luma the codec keeps at full
resolution is a fixed mix of all three channels, so a projection close to it moves little and
one without a channel moves more. Not a test.
"""
import argparse
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from compare_line_dumps import load_profiles  # noqa: E402

LUMINANCE = np.array([0.2126, 0.7152, 0.0722])
STEP_PX = 0.25
MU_GRID = np.arange(-2.0, 2.0001, 0.01)
WIDTH_GRID = np.arange(0.3, 2.0001, 0.05)


class StepFitter:
    """Least-squares fit of c0 + c1·Φ((s − μ)/w) on fixed samples s, μ and w on a grid."""

    def __init__(self, s):
        z = (s[None, None, :] - MU_GRID[:, None, None]) / WIDTH_GRID[None, :, None]
        erf = np.vectorize(__import__("math").erf)
        phi = 0.5 * (1.0 + erf(z / np.sqrt(2.0)))
        self.centred = (phi - phi.mean(-1, keepdims=True)).reshape(-1, len(s))
        self.variance = (self.centred ** 2).sum(-1)

    def mean_px(self, values):
        v = values - values.mean()
        covariance = self.centred @ v
        explained = covariance ** 2 / np.maximum(self.variance, 1e-12)
        best = int(np.argmax(explained))  # least residual = most variance explained
        return MU_GRID[best // len(WIDTH_GRID)]


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--clip", type=float, default=0.95)
    parser.add_argument("--max-lines", type=int, default=400)
    parser.add_argument("dumps", nargs="+")
    args = parser.parse_args()
    if len(args.dumps) < 2:
        sys.exit(__doc__)
    dumps = [load_profiles(path) for path in args.dumps]
    names = [path.rsplit("/", 1)[-1] for path in args.dumps]
    first = next(iter(dumps[0].values()))[2]
    s = (np.arange(len(first)) - len(first) // 2) * STEP_PX
    core = np.abs(s) <= 2.5
    fitter = StepFitter(s[core])
    rng = np.random.default_rng(0)
    print("| camera | rim | lines | clipped | " + " | ".join(f"probe μ {n}" for n in names) +
          " | " + " | ".join(f"luminance μ {n}" for n in names) + " | " +
          " | ".join(f"unclipped μ {n}" for n in names) + " |")
    for camera in sorted({key[0] for key in dumps[0]}):
        for rim in ["up", "down", "left", "right"]:
            keys = [k for k in dumps[0] if k[0] == camera and dumps[0][k][0] == rim and
                    all(k in d for d in dumps[1:])]
            clipped = {k: dumps[0][k][2].max(0) >= args.clip for k in keys}
            for is_clipped in (True, False):
                group = [k for k in keys if clipped[k].any() == is_clipped]
                if not group:
                    continue
                probe = [np.mean([d[k][1] for k in group]) for d in dumps]
                chosen = [group[i] for i in rng.permutation(len(group))[:args.max_lines]]
                luminance, unclipped = [], []
                for d in dumps:
                    full, kept = [], []
                    for k in chosen:
                        profile = d[k][2][core]
                        weights = np.where(clipped[k], 0.0, LUMINANCE)
                        full.append(fitter.mean_px(profile @ LUMINANCE))
                        if weights.any():
                            kept.append(fitter.mean_px(profile @ weights))
                    luminance.append(np.mean(full))
                    unclipped.append(np.mean(kept) if kept else float("nan"))
                cells = [f"{v:+.3f}" for v in probe + luminance + unclipped]
                print(f"| {camera} | {rim} | {len(group)} | {'yes' if is_clipped else 'no'} | " +
                      " | ".join(cells) + " |")


if __name__ == "__main__":
    main()
