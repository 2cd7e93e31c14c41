#!/usr/bin/python3
"""A sequence's ground-truth poses moved by a fixed distance along one camera's image axis.

Usage: /usr/bin/python3 tests/bench/move_poses.py SEQ OUT MM [--camera NAME] [--axis x|y|z]
                                                  [--turn-deg DEG [--seed N]]

Writes OUT/rig_from_object.txt: SEQ's gt/rig_from_object.txt with every object moved by MM (mm)
along the named camera's axis (default cam0's y, so MM > 0 moves the object down in its image;
the direction is expressed in rig coordinates). `edge_bias_probe --at OUT` then measures the
edge lines at those poses: how far each rim's measured offset follows a known move
(docs/notes/issue12_bias_attribution.md, "How stiff each rim is").
--turn-deg also turns every object by DEG degrees about an axis through its origin, drawn at
random per frame (seeded by --seed): `edge_bias_probe --at OUT --solve-out DIR` then shows how
far the edge stage's end point follows a small change of its start
(docs/notes/issue12_edge_fragility.md).
"""
import argparse
import os
import sys

import numpy as np
import yaml


def axis_angle(axis, radians):
    k = np.array([[0.0, -axis[2], axis[1]], [axis[2], 0.0, -axis[0]], [-axis[1], axis[0], 0.0]])
    return np.eye(3) + np.sin(radians) * k + (1.0 - np.cos(radians)) * k @ k


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("sequence")
    parser.add_argument("out")
    parser.add_argument("mm", type=float)
    parser.add_argument("--camera", default="cam0")
    parser.add_argument("--axis", choices=["x", "y", "z"], default="y")
    parser.add_argument("--turn-deg", type=float, default=0.0)
    parser.add_argument("--seed", type=int, default=1)
    args = parser.parse_args()
    rig_path = os.path.join(args.sequence, "rig.yaml")
    poses_path = os.path.join(args.sequence, "gt", "rig_from_object.txt")
    for path in (rig_path, poses_path):
        if not os.path.isfile(path):
            sys.exit(f"move_poses: {path}: not found")
    cameras = {c["name"]: c for c in yaml.safe_load(open(rig_path))["cameras"]}
    if args.camera not in cameras:
        sys.exit(f"move_poses: {rig_path}: no camera '{args.camera}' (has {', '.join(cameras)})")
    cam_from_rig = np.array(cameras[args.camera]["cam_from_rig"], float).reshape(4, 4)
    axis = np.zeros(3)
    axis["xyz".index(args.axis)] = 1.0
    direction = cam_from_rig[:3, :3].T @ axis  # the camera axis in rig coordinates
    poses = np.loadtxt(poses_path, ndmin=2)
    if poses.shape[1] != 12:
        sys.exit(f"move_poses: {poses_path}: {poses.shape[1]} values per row, expected 12")
    poses[:, 9:12] += args.mm * direction
    if args.turn_deg != 0.0:
        random = np.random.default_rng(args.seed)
        for pose in poses:
            axis = random.normal(size=3)
            axis /= np.linalg.norm(axis)
            turn = axis_angle(axis, np.radians(args.turn_deg))
            pose[:9] = (pose[:9].reshape(3, 3) @ turn).reshape(-1)
    os.makedirs(args.out, exist_ok=True)
    np.savetxt(os.path.join(args.out, "rig_from_object.txt"), poses, delimiter="\t", fmt="%.12g")


if __name__ == "__main__":
    main()
