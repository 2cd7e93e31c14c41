#!/usr/bin/env python3
"""Mean linear-RGB profiles of the edge lines in an `edge_bias_probe --dump` file (issue 12).

Usage: edge_profile_groups.py DUMP CAMERA BIN [--step PX]
For the lines of CAMERA whose normal falls in BIN (up, down, left, right), prints the mean
profile per channel every 0.5 px: of all lines, of those whose measured edge μ lies more than
0.25 px inside the true contour, and of those within 0.1 px of it or outside; and a histogram of
μ in 0.25 px bins; and the mean μ weighted as the pose stage weighs the lines (1/σ², σ ≥ 0.1 px). Not a test; the standard library only.
"""
import argparse
from collections import Counter


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("dump")
    parser.add_argument("camera")
    parser.add_argument("bin")
    parser.add_argument("--step", type=float, default=0.25, help="edge.step_px of the dump")
    args = parser.parse_args()
    rows = []
    with open(args.dump) as dump:
        for line in dump:
            fields = line.split()
            if fields[0] != args.camera or fields[2] != args.bin:
                continue
            values = [float(v) for v in fields[9:]]
            rows.append((float(fields[7]), [values[i:i + 3] for i in range(0, len(values), 3)],
                         max(float(fields[8]), 0.1)))
    if not rows:
        raise SystemExit(f"no lines of {args.camera} in bin {args.bin}")
    samples = len(rows[0][1])
    half = (samples - 1) // 2
    every = max(1, round(0.5 / args.step))
    weights = [1.0 / r[2] ** 2 for r in rows]  # the pose stage's weights (σ floored at 0.1 px)
    weighted = sum(w * r[0] for w, r in zip(weights, rows)) / sum(weights)
    print(f"{args.camera} {args.bin}: {len(rows)} lines, mean mu weighted by 1/sigma^2 {weighted:+.3f} px")
    groups = [("all", rows), ("mu < -0.25", [r for r in rows if r[0] < -0.25]),
              ("mu >= -0.1", [r for r in rows if r[0] >= -0.1])]
    for name, group in groups:
        if not group:
            continue
        mean_mu = sum(r[0] for r in group) / len(group)
        print(f"  {name}: {len(group)} lines, mean mu {mean_mu:+.3f} px")
        print("     s " + " ".join(f"{(k - half) * args.step:+6.2f}" for k in range(0, samples, every)))
        for channel, label in enumerate("RGB"):
            means = [sum(r[1][k][channel] for r in group) / len(group) for k in range(0, samples, every)]
            print(f"     {label} " + " ".join(f"{m:6.3f}" for m in means))
    histogram = Counter(int((mu + 2.0) // 0.25) for mu, *_ in rows)
    print("  mu histogram (bin start px: lines): " +
          ", ".join(f"{b * 0.25 - 2.0:+.2f}: {histogram[b]}" for b in sorted(histogram)))


if __name__ == "__main__":
    main()
