#!/usr/bin/python3
"""Per-frame distance between two annotations of the same frames.

Usage: /usr/bin/python3 tests/bench/pose_distance.py A B [--frames]

A and B: rig_from_object.txt files or directories holding one (a sequence's gt/ too). Prints the
mean and largest rotation between them (deg) and the mean and largest distance of the object's
origin (mm) over the frames both have; --frames also each frame's. Frames missing in either
(a line that is not 12 numbers) are skipped.
"""
import argparse
import os
import sys

import numpy as np


def read_poses(path):
    if os.path.isdir(path):
        path = os.path.join(path, "rig_from_object.txt")
    if not os.path.isfile(path):
        sys.exit(f"pose_distance: {path}: not found")
    poses = []
    with open(path) as f:
        for line in f:
            values = line.split()
            poses.append(np.array(values, float) if len(values) == 12 else None)
    return poses


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("a")
    parser.add_argument("b")
    parser.add_argument("--frames", action="store_true")
    args = parser.parse_args()
    rotations, distances = [], []
    for frame, (a, b) in enumerate(zip(read_poses(args.a), read_poses(args.b))):
        if a is None or b is None:
            continue
        relative = a[:9].reshape(3, 3).T @ b[:9].reshape(3, 3)
        cosine = np.clip((np.trace(relative) - 1.0) / 2.0, -1.0, 1.0)
        rotations.append(np.degrees(np.arccos(cosine)))
        distances.append(np.linalg.norm(a[9:] - b[9:]))
        if args.frames:
            print(f"{frame} {rotations[-1]:.4f} {distances[-1]:.4f}")
    if not rotations:
        sys.exit("pose_distance: no frame in both")
    print(f"frames {len(rotations)}"
          f"  rotation mean {np.mean(rotations):.4f} max {np.max(rotations):.4f} deg"
          f"  origin mean {np.mean(distances):.4f} max {np.max(distances):.4f} mm")


if __name__ == "__main__":
    main()
