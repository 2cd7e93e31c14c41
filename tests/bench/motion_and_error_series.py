#!/usr/bin/python3
"""How rough a sequence's true motion is, and how an annotation's rotation error runs over it
(docs/notes/issue12_occlusion_contours.md, the window's weighting).

Usage: tests/bench/motion_and_error_series.py SEQ [ANN]
SEQ: a sequence with gt/rig_from_object.txt and rig.yaml; ANN: its annotation directory.
Prints the true motion's mean rotation per frame and the root mean squares of its angular
acceleration and jerk (deg per frame^2, ^3: the change that a window's motion prior treats as
noise); with ANN, the rotation error about the first camera's y axis per frame (deg), its root
mean square and its autocorrelation at lags 1, 2, 3 and 5. Not a test.
"""
import sys

import numpy as np
import yaml


def load(path):
    a = np.loadtxt(path)
    return a[:, :9].reshape(-1, 3, 3), a[:, 9:]


def log_so3(r):
    """Rotation vector (rad) of a rotation matrix."""
    angle = np.arccos(np.clip((np.trace(r) - 1.0) / 2.0, -1.0, 1.0))
    w = np.array([r[2, 1] - r[1, 2], r[0, 2] - r[2, 0], r[1, 0] - r[0, 1]])
    return w / (2.0 * np.sin(angle)) * angle if angle > 1e-12 else w / 2.0


def main():
    seq = sys.argv[1]
    r_true, _ = load(seq + "/gt/rig_from_object.txt")
    step = np.degrees([log_so3(r_true[i + 1] @ r_true[i].T) for i in range(len(r_true) - 1)])
    acceleration = np.diff(step, axis=0)
    jerk = np.diff(acceleration, axis=0)
    print(f"true motion: {np.linalg.norm(step, axis=1).mean():.2f} deg/frame, angular acceleration "
          f"rms {np.sqrt((acceleration**2).sum(1).mean()):.3f} deg/frame^2, jerk rms "
          f"{np.sqrt((jerk**2).sum(1).mean()):.3f} deg/frame^3")
    if len(sys.argv) < 3:
        return
    r_ann, _ = load(sys.argv[2] + "/rig_from_object.txt")
    rig = yaml.safe_load(open(seq + "/rig.yaml"))
    cam_from_rig = np.array(rig["cameras"][0]["cam_from_rig"]).reshape(4, 4)[:3, :3]
    error = np.degrees([log_so3(r_ann[i] @ r_true[i].T) for i in range(len(r_true))])
    about_y = (error @ cam_from_rig.T)[:, 1]
    lags = [np.corrcoef(about_y[:-k], about_y[k:])[0, 1] for k in (1, 2, 3, 5)]
    print("rotation error about cam0's y axis per frame (deg):", np.round(about_y, 3))
    print(f"rms {np.sqrt((about_y**2).mean()):.3f} deg, autocorrelation at lags 1, 2, 3, 5: "
          + " ".join(f"{c:+.2f}" for c in lags))


if __name__ == "__main__":
    main()
