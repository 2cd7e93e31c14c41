#!/usr/bin/env bash
# `bcot init` on real frames: frame 0 of the BCOT benchmark's Cat sequence
# (../shared/data/bcot_real_cat, one camera, 640×512, handheld in clutter), compared with
# BCOT's own annotation of that frame. The BCOT layout is turned into a bcot sequence first
# (rig.yaml from K.txt, object.yaml, cam0/ as links to the frames; gt/ from pose.txt). Runs:
#   click ±0   one click at the true projection of the mesh's bounding-box centre;
#   click ±10  the same moved by a seeded offset of up to ±10 px per axis (seeds 1..3);
#   no click   the object found by its motion over the 31 frames.
# Prints per run: rotation error (deg), translation error of the object centre (mm), ADD-S / d
# (scripts/init_bench_util.py error) and the time.
# Usage: scripts/bench_bcot_init_real.sh [data dir, default ../shared/data/bcot_real_cat]
# Environment: BCOT_BUILD (default build), BCOT_BENCH_WORK (default out/bench_bcot_init_real).
set -euo pipefail
cd "$(dirname "$0")/.."
data=$(realpath "${1:-../shared/data/bcot_real_cat}")
build=${BCOT_BUILD:-build}
work=${BCOT_BENCH_WORK:-out/bench_bcot_init_real}
if [ ! -d "$data/handheld_demo/Cat" ]; then
  echo "bench_bcot_init_real: $data/handheld_demo/Cat not found" >&2
  exit 2
fi
seq_dir="$work/cat"
rm -rf "$seq_dir"
mkdir -p "$seq_dir/cam0" "$seq_dir/gt"
python3 - "$data" "$seq_dir" <<'PY'
import os, re, sys
data, seq = sys.argv[1], sys.argv[2]
k = [float(x) for x in re.findall(r"[-+]?\d*\.\d+|[-+]?\d+", open(os.path.join(data, "handheld_demo/K.txt")).read().split("(", 1)[1])]
fx, cx, fy, cy = k[0], k[2], k[4], k[5]
with open(os.path.join(seq, "rig.yaml"), "w") as f:
    f.write("cameras:\n  - name: cam0\n    image_size: [640, 512]\n")
    f.write("    K: [%r, %r, %r, %r]\n" % (fx, fy, cx, cy))
    f.write("    cam_from_rig: [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1]\n")
with open(os.path.join(seq, "object.yaml"), "w") as f:
    f.write("name: Cat\nmesh: %s\nunit_to_mm: 1\n" % os.path.join(data, "models/Cat.obj"))
frames = sorted(x for x in os.listdir(os.path.join(data, "handheld_demo/Cat")) if x.endswith(".png"))
for i, name in enumerate(frames):
    os.symlink(os.path.join(data, "handheld_demo/Cat", name), os.path.join(seq, "cam0", "%06d.png" % i))
with open(os.path.join(data, "handheld_demo/Cat/pose.txt")) as src, \
        open(os.path.join(seq, "gt/rig_from_object.txt"), "w") as dst:
    for line in src:
        v = line.split()
        if len(v) == 12:
            dst.write(" ".join(v) + "\n")
PY
rows="$work/rows.txt"
: >"$rows"
run() {  # label, then bcot init arguments
  local label=$1
  shift
  local out="$work/$(echo "$label" | tr ' ±' '__').txt"
  local start seconds deg mm adds
  start=$(date +%s.%N)
  if "$build/bcot" init "$seq_dir" "$@" --out "$out" --overwrite >"$out.log" 2>&1; then
    seconds=$(echo "$(date +%s.%N) - $start" | bc)
    read -r deg mm adds <<<"$(python3 scripts/init_bench_util.py error "$seq_dir" 0 "$out")"
  else
    seconds=$(echo "$(date +%s.%N) - $start" | bc)
    deg=failed mm=- adds=-
  fi
  printf '| %s | %s | %s | %s | %.1f |\n' "$label" "$deg" "$mm" "$adds" "$seconds" | tee -a "$rows"
}
echo "| start | rotation (deg) | translation (mm) | ADD-S / d | time (s) |"
echo "|---|---:|---:|---:|---:|"
read -ra click <<<"$(python3 scripts/init_bench_util.py clicks "$seq_dir" 0 cam0 0 1)"
run "click ±0" "${click[@]}"
for seed in 1 2 3; do
  read -ra click <<<"$(python3 scripts/init_bench_util.py clicks "$seq_dir" 0 cam0 10 "$seed")"
  run "click ±10 (seed $seed)" "${click[@]}"
done
run "no click" 
