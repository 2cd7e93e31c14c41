#!/usr/bin/env python3
"""Helpers of scripts/bench_bcot_init.sh (standard library + PyYAML only).

  init_bench_util.py clicks SEQ FRAME CAMERAS JITTER_PX SEED
      prints `--click CAM:X,Y` for each camera in CAMERAS (comma separated): the true projection
      of the object centre (bounding-box centre of the mesh) at FRAME from SEQ/gt, moved by a
      uniform random offset in [-JITTER_PX, JITTER_PX] per axis.
  init_bench_util.py error SEQ FRAME POSE_FILE
      prints "ROTATION_DEG TRANSLATION_MM ADDS_OVER_D" of POSE_FILE's first pose against SEQ/gt
      at FRAME: the rotation error, the translation error of the object centre (rig frame), and
      ADD-S (the mean distance from each of up to 400 mesh vertices at the estimate to the
      nearest vertex at the truth, which does not count errors along a symmetry of the object)
      over the longest bounding-box side d.
"""
import math
import os
import random
import sys

import yaml


def read_poses(path):
    poses = []
    with open(path) as f:
        for line in f:
            v = [float(x) for x in line.split()]
            if len(v) == 12:
                poses.append(([v[0:3], v[3:6], v[6:9]], v[9:12]))
    return poses


def apply(pose, p):
    r, t = pose
    return [sum(r[i][k] * p[k] for k in range(3)) + t[i] for i in range(3)]


def mesh_vertices(seq):
    with open(os.path.join(seq, "object.yaml")) as f:
        obj = yaml.safe_load(f)
    path = os.path.join(seq, obj["mesh"])
    scale = float(obj.get("unit_to_mm", 1.0))
    verts = []
    with open(path) as f:
        lines = f.read().split("\n")
    if path.lower().endswith(".off"):
        tokens = " ".join(l.split("#")[0] for l in lines).split()
        n = int(tokens[1])
        for i in range(n):
            verts.append([float(x) for x in tokens[4 + 3 * i:7 + 3 * i]])
    else:
        for line in lines:
            if line.startswith("v "):
                verts.append([float(x) for x in line.split()[1:4]])
    return [[x * scale for x in v] for v in verts]


def bbox(verts):
    lo = [min(v[i] for v in verts) for i in range(3)]
    hi = [max(v[i] for v in verts) for i in range(3)]
    return lo, hi


def mesh_centre(seq):
    lo, hi = bbox(mesh_vertices(seq))
    return [0.5 * (lo[i] + hi[i]) for i in range(3)]


def adds_over_d(seq, gt, est):
    verts = mesh_vertices(seq)
    lo, hi = bbox(verts)
    d = max(hi[i] - lo[i] for i in range(3))
    step = max(1, len(verts) // 400)
    truth = [apply(gt, v) for v in verts[::max(1, len(verts) // 2000)]]
    total = 0.0
    count = 0
    for v in verts[::step]:
        p = apply(est, v)
        total += math.sqrt(min((p[0] - q[0]) ** 2 + (p[1] - q[1]) ** 2 + (p[2] - q[2]) ** 2
                               for q in truth))
        count += 1
    return total / count / d


def project(cam, p):
    fx, fy, cx, cy = cam["K"]
    k1, k2, p1, p2, k3 = (cam.get("distortion") or [0, 0, 0, 0, 0])
    x, y = p[0] / p[2], p[1] / p[2]
    r2 = x * x + y * y
    radial = 1 + k1 * r2 + k2 * r2 * r2 + k3 * r2 * r2 * r2
    xd = x * radial + 2 * p1 * x * y + p2 * (r2 + 2 * x * x)
    yd = y * radial + p1 * (r2 + 2 * y * y) + 2 * p2 * x * y
    return fx * xd + cx, fy * yd + cy


def clicks(seq, frame, cameras, jitter, seed):
    rng = random.Random(seed)
    with open(os.path.join(seq, "rig.yaml")) as f:
        rig = {c["name"]: c for c in yaml.safe_load(f)["cameras"]}
    gt = read_poses(os.path.join(seq, "gt", "rig_from_object.txt"))[frame]
    centre = apply(gt, mesh_centre(seq))
    out = []
    for name in cameras.split(","):
        m = rig[name]["cam_from_rig"]
        pose = ([m[0:3], m[4:7], m[8:11]], [m[3], m[7], m[11]])
        u, v = project(rig[name], apply(pose, centre))
        u += rng.uniform(-jitter, jitter)
        v += rng.uniform(-jitter, jitter)
        out.append("--click %s:%.2f,%.2f" % (name, u, v))
    print(" ".join(out))


def error(seq, frame, pose_file):
    gt = read_poses(os.path.join(seq, "gt", "rig_from_object.txt"))[frame]
    est = read_poses(pose_file)[0]
    ra, rb = gt[0], est[0]
    trace = sum(ra[k][i] * rb[k][i] for i in range(3) for k in range(3))
    deg = math.degrees(math.acos(max(-1.0, min(1.0, (trace - 1) / 2))))
    c = mesh_centre(seq)
    a, b = apply(gt, c), apply(est, c)
    mm = math.sqrt(sum((a[i] - b[i]) ** 2 for i in range(3)))
    print("%.3f %.3f %.4f" % (deg, mm, adds_over_d(seq, gt, est)))


if __name__ == "__main__":
    if len(sys.argv) == 7 and sys.argv[1] == "clicks":
        clicks(sys.argv[2], int(sys.argv[3]), sys.argv[4], float(sys.argv[5]), int(sys.argv[6]))
    elif len(sys.argv) == 5 and sys.argv[1] == "error":
        error(sys.argv[2], int(sys.argv[3]), sys.argv[4])
    else:
        sys.exit(__doc__)
