#!/usr/bin/env python3
"""Paired comparison of two annotations of the same rendered sequences, with standard errors.

A change to the annotator moves each frame's error a little, and on a small or fast object the
tracking then takes a different path for many frames: two runs of 40 frames that differ in the
third decimal of a line fit can differ by 0.03 deg in mean rotation error with no better or worse
method behind it. This script says how large a difference must be to mean something. Per scene
it takes the per-frame errors of both annotations (`pbr_errors SEQ ANN --blocks 1`, each
camera's frame), their difference frame by frame, and the standard error of its mean by batch
means: the frames are cut into consecutive batches of --batch frames, so that an error that
persists over a few frames (the tracking's memory) is counted once per batch, not once per
frame. Over all scenes the differences are averaged with equal weight per scene, and their
standard errors combined as independent.

Columns (B − A; + = B is worse):
  rotation     mean rotation error (deg)
  |t|          mean |error| over the x, y, z axes and the cameras (mm)
  |bias y|     |mean signed y error| per camera, averaged over the cameras (mm): the vertical
               bias of issue 12 (its standard error is that of the signed mean's difference)

Several runs per side (--a ROOT ROOT ..., --b ROOT ROOT ...) are averaged frame by frame before
the difference is taken. Runs of the same settings started from slightly different points
(`--set tracker.velocity_prediction=0.999`, 0.998, ...: a start 0.1 % of a frame's motion
away, which changes nothing systematically) sample the tracking's path-dependence, so that a
setting is compared with another, not one run's luck with another's.

Usage:
  scripts/pbr/compare_annotations.py [--pbr-errors build/tests/bench/pbr_errors] SEQ_ROOT \\
      --a ANN_ROOT [ANN_ROOT ...] --b ANN_ROOT [ANN_ROOT ...] [--scenes NAME ...] [--batch 5]
SEQ_ROOT holds the rendered sequences; each ANN_ROOT holds one annotation per sequence, named as
the sequence (as `bcot batch` and scripts/pbr/annotate_seeds.sh write them) or as the sequence
without the hash suffix scripts/pbr_synth.sh gives it (`name-<hash>`). Needs numpy
(scripts/setup.sh --with-blender).
"""
import argparse
import glob
import os
import subprocess
import sys

import numpy as np


# Columns of per_frame_errors' rows.
ROTATION, ABS_XYZ, SIGNED_Y = 0, slice(1, 4), 5


def per_frame_errors(pbr_errors, sequence, annotation):
    """{camera: array of rows (rot, abs x, abs y, abs z, signed x, signed y, signed z)}: the
    per-frame lines of `pbr_errors --blocks 1` (frames, rot_max, the stds, worst, lost left out)."""
    run = subprocess.run([pbr_errors, sequence, annotation, "--blocks", "1"],
                         capture_output=True, text=True)
    if run.returncode != 0:
        sys.exit(f"compare_annotations: {pbr_errors} {sequence} {annotation} failed:\n"
                 f"{run.stderr.strip()}")
    out = run.stdout
    rows = {}
    for line in out.splitlines():
        fields = line.split("\t")
        if "#" not in fields[0]:
            continue
        camera = fields[0].split("#")[0]
        rows.setdefault(camera, []).append([float(v) for v in fields[2:3] + fields[4:10]])
    return {camera: np.array(values) for camera, values in rows.items()}


def batch_mean_se(series, batch):
    """Mean of `series` and its standard error by non-overlapping batch means."""
    n = len(series) // batch
    if n < 2:
        return float(np.mean(series)), float("nan")
    means = np.asarray(series[:n * batch]).reshape(n, batch).mean(axis=1)
    return float(np.mean(series)), float(np.std(means, ddof=1) / np.sqrt(n))


def mean_of_runs(runs):
    """Frame-by-frame mean of several runs' per_frame_errors (the frames all runs have)."""
    cameras = sorted(set.intersection(*(set(run) for run in runs)))
    frames = min(len(run[c]) for run in runs for c in cameras)
    return {c: np.mean([run[c][:frames] for run in runs], axis=0) for c in cameras}


def scene_differences(a, b, batch):
    """(value A, value B, difference, its standard error) for each column of the header."""
    cameras = sorted(set(a) & set(b))
    frames = min(min(len(a[c]), len(b[c])) for c in cameras)
    a = {c: a[c][:frames] for c in cameras}
    b = {c: b[c][:frames] for c in cameras}
    first = cameras[0]
    result = {}
    # Rotation: one pose per frame, the same angle in every camera.
    ra, rb = a[first][:, ROTATION], b[first][:, ROTATION]
    mean, se = batch_mean_se(rb - ra, batch)
    result["rotation"] = (ra.mean(), rb.mean(), mean, se)
    # |t|: per frame the mean |error| over axes and cameras.
    ta = np.mean([a[c][:, ABS_XYZ].mean(axis=1) for c in cameras], axis=0)
    tb = np.mean([b[c][:, ABS_XYZ].mean(axis=1) for c in cameras], axis=0)
    mean, se = batch_mean_se(tb - ta, batch)
    result["|t|"] = (ta.mean(), tb.mean(), mean, se)
    # |bias y| per camera, then averaged; se from the signed y's paired difference.
    bias_a = np.mean([abs(a[c][:, SIGNED_Y].mean()) for c in cameras])
    bias_b = np.mean([abs(b[c][:, SIGNED_Y].mean()) for c in cameras])
    ses = [batch_mean_se(b[c][:, SIGNED_Y] - a[c][:, SIGNED_Y], batch)[1] for c in cameras]
    result["|bias y|"] = (bias_a, bias_b, bias_b - bias_a, float(np.sqrt(np.mean(np.square(ses)))))
    return result


def cell(value_a, value_b, difference, se):
    return f"{value_a:.4f} → {value_b:.4f} ({difference:+.4f} ± {se:.4f})"


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("seq_root")
    parser.add_argument("--a", nargs="+", required=True, help="annotation roots of setting A")
    parser.add_argument("--b", nargs="+", required=True, help="annotation roots of setting B")
    parser.add_argument("--pbr-errors", default="build/tests/bench/pbr_errors")
    parser.add_argument("--scenes", nargs="*", help="scene names (default: every annotation in A)")
    parser.add_argument("--batch", type=int, default=5, help="frames per batch (default 5)")
    args = parser.parse_args()
    if args.batch < 1:
        sys.exit("compare_annotations: --batch must be >= 1")
    if not os.access(args.pbr_errors, os.X_OK):
        sys.exit(f"compare_annotations: {args.pbr_errors} is not an executable (--pbr-errors)")
    for root in [args.seq_root] + args.a + args.b:
        if not os.path.isdir(root):
            sys.exit(f"compare_annotations: {root} is not a directory")

    scenes = args.scenes or sorted(
        name for name in os.listdir(args.a[0])
        if os.path.isfile(os.path.join(args.a[0], name, "rig_from_object.txt")))
    columns = ["rotation", "|t|", "|bias y|"]
    totals = {c: [] for c in columns}
    print("| scene | " + " | ".join(f"{c} A → B (B − A ± se)" for c in columns) + " |")
    print("|---" * (len(columns) + 1) + "|")
    for scene in scenes:
        matches = sorted(glob.glob(os.path.join(args.seq_root, scene)) +
                         glob.glob(os.path.join(args.seq_root, scene + "-*")))
        matches = [m for m in matches if os.path.isdir(m)]
        if not matches:
            sys.exit(f"compare_annotations: no sequence {scene} in {args.seq_root}")
        sides = []
        for roots in (args.a, args.b):
            runs = []
            for root in roots:
                path = os.path.join(root, scene)
                if not os.path.isfile(os.path.join(path, "rig_from_object.txt")):
                    sys.exit(f"compare_annotations: {path}/rig_from_object.txt does not exist")
                runs.append(per_frame_errors(args.pbr_errors, matches[0], path))
            sides.append(mean_of_runs(runs))
        a, b = sides
        result = scene_differences(a, b, args.batch)
        for c in columns:
            totals[c].append(result[c])
        cells = [cell(*result[c]) for c in columns]
        print(f"| {scene} | " + " | ".join(cells) + " |")
    cells = []
    for c in columns:
        values = np.array(totals[c])
        se = np.sqrt(np.sum(np.square(values[:, 3]))) / len(values)
        cells.append(cell(*values[:, :3].mean(axis=0), se))
    print(f"| **mean of {len(scenes)}** | " + " | ".join(cells) + " |")


if __name__ == "__main__":
    main()
