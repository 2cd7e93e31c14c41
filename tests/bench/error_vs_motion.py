#!/usr/bin/python3
"""Whether an annotation's pose error follows the object's motion (a solver or window lag).

Usage: /usr/bin/python3 tests/bench/error_vs_motion.py SEQ ANN

SEQ has gt/rig_from_object.txt (bcot synth, scripts/pbr_synth.sh), ANN is `bcot annotate`'s
output. Per frame, in the rig's frame: the rotation error φ = log(R·R_gtᵀ) (degrees) and the
true angular velocity ω = log(R_gt(k+1)·R_gt(k−1)ᵀ)/2 (degrees per frame; one-sided at the
ends), the translation error and the true velocity (mm, mm per frame). Prints per axis the mean
and standard deviation of the error, its correlation with the velocity and the slope of the
least-squares line error = slope·velocity + intercept: a lag shows as a slope of a sizeable
fraction of a frame with a high correlation, a bias that does not follow the motion as an
intercept with none. Then the mean rotation error ‖φ‖ as it is, with each axis's mean taken
out, and with all three: how much of the error is bias and how much scatter.
"""
import sys

import cv2
import numpy as np


def load(path):
    m = np.loadtxt(path, ndmin=2)
    return m[:, :9].reshape(-1, 3, 3), m[:, 9:12]


def log_deg(r):
    v, _ = cv2.Rodrigues(r)
    return np.degrees(v.ravel())


def central(values, n, difference):
    out = []
    for k in range(n):
        a, b = max(k - 1, 0), min(k + 1, n - 1)
        out.append(difference(values[b], values[a]) / (b - a))
    return np.array(out)


def report(label, error, velocity):
    print(f"{label}: error mean {np.round(error.mean(0), 4)} sd {np.round(error.std(0), 4)}")
    for axis in range(3):
        corr = np.corrcoef(error[:, axis], velocity[:, axis])[0, 1]
        slope, intercept = np.polyfit(velocity[:, axis], error[:, axis], 1)
        print(f"  axis {'xyz'[axis]}: corr(error, velocity) {corr:+.2f}, slope {slope:+.4f} "
              f"frames, intercept {intercept:+.4f}")


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    r_gt, t_gt = load(sys.argv[1] + "/gt/rig_from_object.txt")
    r_an, t_an = load(sys.argv[2] + "/rig_from_object.txt")
    if len(r_gt) != len(r_an):
        sys.exit(f"{len(r_an)} annotated poses for {len(r_gt)} frames")
    n = len(r_gt)
    phi = np.array([log_deg(r_an[k] @ r_gt[k].T) for k in range(n)])
    omega = central(r_gt, n, lambda b, a: log_deg(b @ a.T))
    velocity = central(t_gt, n, lambda b, a: b - a)
    report("rotation (deg, rig axes)", phi, omega)
    # How much of the rotation error the means are: the mean ‖φ‖ with each axis's mean taken
    # out, and with all three.
    norms = [np.linalg.norm(phi, axis=1).mean()]
    for axis in range(3):
        centred = phi.copy()
        centred[:, axis] -= centred[:, axis].mean()
        norms.append(np.linalg.norm(centred, axis=1).mean())
    norms.append(np.linalg.norm(phi - phi.mean(0), axis=1).mean())
    print("  mean |phi| %.4f; without the mean about x / y / z %.4f / %.4f / %.4f; "
          "without all three %.4f" % tuple(norms))
    report("translation (mm, rig axes)", t_an - t_gt, velocity)


if __name__ == "__main__":
    main()
