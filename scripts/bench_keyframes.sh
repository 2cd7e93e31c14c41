#!/usr/bin/env bash
# Keyframes mend a lost stretch: a `bcot synth` sequence (configs/synth/demo.yaml, 40 frames, the
# object turning 6° and moving 4 mm per frame,
# binocular 640×512) with 8 frames dropped in the middle, so the object jumps by 8 frames of
# motion between frames 19 and 20 and tracking loses it. The sequence is annotated
# (configs/annotate.yaml) without keyframes, then with one keyframe at frame 20 found by
# `bcot init --frame 20` from two clicks (true projected centre moved by up to ±10 px), as a
# user would set it. Prints per part of the sequence (frames 0–19 before the jump, 20–31 after)
# the mean and largest rotation (deg) and translation (mm, object centre) errors against gt/ and
# the frames off by more than 5° or 10 mm, without and with the keyframe.
# Usage: scripts/bench_keyframes.sh [seed, default 5]
# Environment: BCOT_BUILD (default build), BCOT_BENCH_WORK (default out/bench_keyframes).
set -euo pipefail
cd "$(dirname "$0")/.."
seed=${1:-5}
build=${BCOT_BUILD:-build}
work=${BCOT_BENCH_WORK:-out/bench_keyframes}
rm -rf "$work"
mkdir -p "$work"
"$build/bcot" synth --quiet --config configs/synth/demo.yaml --out "$work/full" \
  --set seed="$seed" --set motion.num_frames=40 --set motion.rotation_deg_per_frame=6 \
  --set motion.translation_mm_per_frame=4
seq="$work/seq"
python3 - "$work/full" "$seq" <<'PY'
import os, shutil, sys
full, seq = sys.argv[1], sys.argv[2]
keep = list(range(0, 20)) + list(range(28, 40))
os.makedirs(os.path.join(seq, "gt"))
for name in ("rig.yaml", "object.yaml", "init_pose.txt"):
    shutil.copy(os.path.join(full, name), os.path.join(seq, name))
shutil.copytree(os.path.join(full, "model"), os.path.join(seq, "model"))
for cam in ("cam0", "cam1"):
    os.makedirs(os.path.join(seq, cam))
    ext = os.path.splitext(sorted(os.listdir(os.path.join(full, cam)))[0])[1]
    for new, old in enumerate(keep):
        shutil.copy(os.path.join(full, cam, "%06d%s" % (old, ext)),
                    os.path.join(seq, cam, "%06d%s" % (new, ext)))
lines = open(os.path.join(full, "gt/rig_from_object.txt")).read().split("\n")
poses = [l for l in lines if len(l.split()) == 12]
with open(os.path.join(seq, "gt/rig_from_object.txt"), "w") as f:
    f.write("\n".join(poses[i] for i in keep) + "\n")
PY
"$build/bcot" annotate --quiet "$seq" --out "$work/without" --config configs/annotate.yaml || true
read -ra clicks <<<"$(python3 scripts/init_bench_util.py clicks "$seq" 20 cam0,cam1 10 "$seed")"
"$build/bcot" init "$seq" --frame 20 "${clicks[@]}" --out "$work/kf20.txt" --quiet
printf '20 %s\n' "$(grep -v '^#' "$work/kf20.txt" | head -1)" >"$seq/keyframes.txt"
"$build/bcot" annotate --quiet "$seq" --out "$work/with" --config configs/annotate.yaml || true
python3 - "$seq" "$work" <<'PY'
import math, os, sys
sys.path.insert(0, "scripts")
import init_bench_util as u
seq, work = sys.argv[1], sys.argv[2]
gt = u.read_poses(os.path.join(seq, "gt/rig_from_object.txt"))
centre = u.mesh_centre(seq)
def errors(path):
    est = u.read_poses(path)
    out = []
    for g, e in zip(gt, est):
        rg, re_ = g[0], e[0]
        trace = sum(rg[k][i] * re_[k][i] for i in range(3) for k in range(3))
        deg = math.degrees(math.acos(max(-1.0, min(1.0, (trace - 1) / 2))))
        mm = math.dist(u.apply(g, centre), u.apply(e, centre))
        out.append((deg, mm))
    return out
print("| annotation | frames | mean rot (deg) | max rot (deg) | mean t (mm) | max t (mm) | off > 5° / 10 mm |")
print("|---|---|---:|---:|---:|---:|---:|")
for label in ("without", "with"):
    err = errors(os.path.join(work, label, "rig_from_object.txt"))
    for part, frames in (("0–19", range(0, 20)), ("20–31", range(20, len(err)))):
        e = [err[i] for i in frames]
        off = sum(d > 5 or m > 10 for d, m in e)
        print("| %s keyframe | %s | %.3f | %.3f | %.3f | %.3f | %d |" % (
            label, part, sum(d for d, _ in e) / len(e), max(d for d, _ in e),
            sum(m for _, m in e) / len(e), max(m for _, m in e), off))
PY
