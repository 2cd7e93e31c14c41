#!/usr/bin/env bash
# `bcot init` without init_pose.txt: success rate and time per init on bcot synth sequences.
# One frame per sequence, configs/synth/demo.yaml (binocular 90°, 640×512, cluttered and plain
# backdrops) with the bunny, the spool and the pinion meshes and several seeds (object pose,
# scene, distractors). Two ways of clicking the object centre (the true projection of the
# mesh's bounding-box centre moved by a seeded uniform offset of up to ±JITTER px per axis):
#   2 clicks: cam0 and cam1 (the centre is triangulated);
#   1 click:  cam0 only (the depth along the ray is searched with the orientation).
# A run succeeds when the written pose is within 5° and 10 mm (object centre) of gt/.
# Prints one row per sequence and mode, then the table: success rate and mean time per init.
#
# Usage: scripts/bench_bcot_init.sh [seeds per object, default 4] [jitter px, default 10]
# Environment: BCOT_BENCH_WORK (default out/bench_bcot_init), BCOT_BUILD (default build).
set -euo pipefail
cd "$(dirname "$0")/.."
seeds=${1:-4}
jitter=${2:-10}
work=${BCOT_BENCH_WORK:-out/bench_bcot_init}
build=${BCOT_BUILD:-build}
bcot="$build/bcot"
if [ ! -x "$bcot" ]; then
  cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
  cmake --build "$build" --target bcot >/dev/null
fi
mkdir -p "$work"
rows="$work/rows.txt"
: >"$rows"
for object in bunny.obj spool.off pinion.off; do
  for seed in $(seq 1 "$seeds"); do
    seq_dir="$work/${object%%.*}_$seed"
    if [ ! -f "$seq_dir/rig.yaml" ]; then
      "$bcot" synth --quiet --config configs/synth/demo.yaml --out "$seq_dir" \
        --set seed="$seed" --set motion.num_frames=1 \
        --set object.mesh="$PWD/data/meshes/$object" >/dev/null 2>"$seq_dir.synth.log"
      rm -f "$seq_dir/init_pose.txt"
    fi
    for mode in 2 1; do
      cameras=$([ "$mode" = 2 ] && echo cam0,cam1 || echo cam0)
      read -ra clicks <<<"$(python3 scripts/init_bench_util.py clicks "$seq_dir" 0 "$cameras" \
        "$jitter" "$seed")"
      out="$work/${object%%.*}_${seed}_${mode}click.txt"
      start=$(date +%s.%N)
      if "$bcot" init "$seq_dir" "${clicks[@]}" --out "$out" --overwrite \
        >"$out.log" 2>&1; then
        seconds=$(echo "$(date +%s.%N) - $start" | bc)
        read -r deg mm <<<"$(python3 scripts/init_bench_util.py error "$seq_dir" 0 "$out")"
      else
        seconds=$(echo "$(date +%s.%N) - $start" | bc)
        deg=nan mm=nan
      fi
      printf '%s %s %s %s %s\n' "${object%%.*}_$seed" "$mode" "$deg" "$mm" "$seconds" | tee -a "$rows"
    done
  done
done
python3 - "$rows" "$jitter" <<'PY'
import math, sys
rows = [l.split() for l in open(sys.argv[1]) if l.strip()]
print()
print("| clicks (±%s px) | sequences | within 5° / 10 mm | mean time per init (s) | median error (deg / mm) |" % sys.argv[2])
print("|---|---:|---:|---:|---:|")
for mode, label in (("2", "2 views"), ("1", "1 view, depth searched")):
    sel = [r for r in rows if r[1] == mode]
    ok = [r for r in sel if r[2] != "nan" and float(r[2]) <= 5 and float(r[3]) <= 10]
    degs = sorted(float(r[2]) for r in sel if r[2] != "nan")
    mms = sorted(float(r[3]) for r in sel if r[3] != "nan")
    med = lambda v: v[len(v) // 2] if v else float("nan")
    print("| %s | %d | %d / %d (%.0f %%) | %.1f | %.2f / %.2f |" % (
        label, len(sel), len(ok), len(sel), 100.0 * len(ok) / max(1, len(sel)),
        sum(float(r[4]) for r in sel) / max(1, len(sel)), med(degs), med(mms)))
PY
