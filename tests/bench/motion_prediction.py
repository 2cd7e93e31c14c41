#!/usr/bin/python3
"""How far a sequence's true motion is from what a constant-velocity prediction expects.

Usage: /usr/bin/python3 tests/bench/motion_prediction.py SEQ [--per-frame]

SEQ has gt/rig_from_object.txt and object.yaml (bcot synth, scripts/pbr_synth.sh, or a copy
from tests/bench/subsample_sequence.py). The tracker starts each frame at the last pose moved
on by the last motion (MultiViewTracker, velocity_prediction 1). Prints, for the object's
bounding-box centre (mm) and its rotation (deg): the mean and largest step from one frame to
the next, and the mean and largest error of that prediction (the true pose against the last
pose moved on by the last motion), with the mesh's largest extent for scale
(docs/notes/issue12_fast_motion.md); --per-frame also lists each frame's step and prediction
error. Not a test.
"""
import os
import sys

import numpy as np
import yaml

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..",
                                "scripts", "pbr"))
import pbr_common as pc  # noqa: E402


def angle_deg(rotation):
    return np.degrees(np.arccos(np.clip((np.trace(rotation) - 1.0) / 2.0, -1.0, 1.0)))


def main():
    if len(sys.argv) not in (2, 3) or (len(sys.argv) == 3 and sys.argv[2] != "--per-frame"):
        sys.exit(__doc__)
    seq = sys.argv[1]
    per_frame = len(sys.argv) == 3
    poses_path = os.path.join(seq, "gt", "rig_from_object.txt")
    object_path = os.path.join(seq, "object.yaml")
    for path in (poses_path, object_path):
        if not os.path.isfile(path):
            sys.exit(f"motion_prediction: {path}: not found")
    obj = yaml.safe_load(open(object_path))
    vertices, _ = pc.load_mesh_arrays(os.path.join(seq, obj["mesh"]))
    vertices = np.asarray(vertices, float) * float(obj.get("unit_to_mm", 1.0))
    centre = (vertices.min(axis=0) + vertices.max(axis=0)) / 2.0
    poses = np.loadtxt(poses_path, ndmin=2)
    if len(poses) < 3:
        sys.exit(f"motion_prediction: {poses_path}: fewer than 3 frames")
    rotations = poses[:, :9].reshape(-1, 3, 3)
    centres = np.array([r @ centre + t for r, t in zip(rotations, poses[:, 9:12])])
    step_mm = np.linalg.norm(np.diff(centres, axis=0), axis=1)
    error_mm = np.linalg.norm(centres[2:] - 2.0 * centres[1:-1] + centres[:-2], axis=1)
    step_deg = np.array([angle_deg(rotations[k] @ rotations[k - 1].T)
                         for k in range(1, len(rotations))])
    error_deg = np.array([
        angle_deg(rotations[k] @ (rotations[k - 1] @ rotations[k - 2].T @ rotations[k - 1]).T)
        for k in range(2, len(rotations))])
    print(f"{seq}: {len(poses)} frames, object {np.ptp(vertices, axis=0).max():.0f} mm")
    if per_frame:
        for k in range(2, len(poses)):
            print(f"  frame {k}: step {step_mm[k - 1]:.1f} mm, {step_deg[k - 1]:.2f} deg; "
                  f"prediction error {error_mm[k - 2]:.1f} mm, {error_deg[k - 2]:.2f} deg")
    print(f"  centre step mean / max {step_mm.mean():.1f} / {step_mm.max():.1f} mm, "
          f"prediction error mean / max {error_mm.mean():.1f} / {error_mm.max():.1f} mm")
    print(f"  rotation step mean / max {step_deg.mean():.2f} / {step_deg.max():.2f} deg, "
          f"prediction error mean / max {error_deg.mean():.2f} / {error_deg.max():.2f} deg")


if __name__ == "__main__":
    main()
