#!/usr/bin/python3
"""A sequence's ground-truth poses turned by a fixed angle about a random axis per frame.

Usage: /usr/bin/python3 tests/bench/turn_poses.py SEQ OUT DEG [--seed N]

Writes OUT/rig_from_object.txt: SEQ's gt/rig_from_object.txt with every object turned by DEG
degrees about an axis through its origin, drawn at random per frame (seeded). `edge_bias_probe
--at OUT --solve-out DIR` then runs the edge stage from those starts: how far its end point
follows a small change of its start (docs/notes/issue12_edge_fragility.md).
"""
import argparse
import os
import sys

import numpy as np


def axis_angle(axis, radians):
    k = np.array([[0.0, -axis[2], axis[1]], [axis[2], 0.0, -axis[0]], [-axis[1], axis[0], 0.0]])
    return np.eye(3) + np.sin(radians) * k + (1.0 - np.cos(radians)) * k @ k


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("sequence")
    parser.add_argument("out")
    parser.add_argument("deg", type=float)
    parser.add_argument("--seed", type=int, default=1)
    args = parser.parse_args()
    poses_path = os.path.join(args.sequence, "gt", "rig_from_object.txt")
    if not os.path.isfile(poses_path):
        sys.exit(f"turn_poses: {poses_path}: not found")
    poses = np.loadtxt(poses_path, ndmin=2)
    if poses.shape[1] != 12:
        sys.exit(f"turn_poses: {poses_path}: expected 12 numbers per line, found {poses.shape[1]}")
    random = np.random.default_rng(args.seed)
    for pose in poses:
        axis = random.normal(size=3)
        axis /= np.linalg.norm(axis)
        rotation = pose[:9].reshape(3, 3) @ axis_angle(axis, np.radians(args.deg))
        pose[:9] = rotation.reshape(-1)
    os.makedirs(args.out, exist_ok=True)
    np.savetxt(os.path.join(args.out, "rig_from_object.txt"), poses, fmt="%.12g")


if __name__ == "__main__":
    main()
