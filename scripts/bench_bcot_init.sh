#!/usr/bin/env bash
# `bcot init` without init_pose.txt: success rate and time per init on bcot synth sequences.
# One frame per sequence, configs/synth/demo.yaml (binocular 90°, 640×512, cluttered and plain
# backdrops) with each mesh of BCOT_BENCH_MESHES (default: the bunny, the spool and the pinion of
# data/meshes) and several seeds (object pose, scene, distractors). Two ways of clicking the object centre (the true projection of the
# mesh's bounding-box centre moved by a seeded uniform offset of up to ±JITTER px per axis):
#   2 clicks: cam0 and cam1 (the centre is triangulated);
#   1 click:  cam0 only (the depth along the ray is searched with the orientation).
# A run succeeds when the written pose is within 5° and 10 mm (object centre) of gt/. The spool
# and the pinion are (nearly) rotationally symmetric, so their rotation about the axis is not
# defined by the images: the table also counts ADD-S < 0.1 d (mean distance of the model points
# to the nearest model point of the truth, d the longest bounding-box side; the BOP criterion
# for symmetric objects). Prints one row per sequence and mode, then the tables: per mode and
# per mesh, success rates and mean time per init.
#
# Usage: scripts/bench_bcot_init.sh [seeds per object, default 4] [jitter px, default 10]
# Environment: BCOT_BENCH_WORK (default out/bench_bcot_init), BCOT_BUILD (default build),
# BCOT_BENCH_MESHES (space-separated mesh files, default the three of data/meshes).
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
read -ra meshes <<<"${BCOT_BENCH_MESHES:-data/meshes/bunny.obj data/meshes/spool.off data/meshes/pinion.off}"
for mesh in "${meshes[@]}"; do
  mesh=$(realpath "$mesh")
  object=$(basename "$mesh")
  for seed in $(seq 1 "$seeds"); do
    seq_dir="$work/${object%%.*}_$seed"
    if [ ! -f "$seq_dir/rig.yaml" ]; then
      "$bcot" synth --quiet --config configs/synth/demo.yaml --out "$seq_dir" \
        --set seed="$seed" --set motion.num_frames=1 \
        --set object.mesh="$mesh" >/dev/null 2>"$seq_dir.synth.log"
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
        read -r deg mm adds <<<"$(python3 scripts/init_bench_util.py error "$seq_dir" 0 "$out")"
      else
        seconds=$(echo "$(date +%s.%N) - $start" | bc)
        deg=nan mm=nan adds=nan
      fi
      printf '%s %s %s %s %s %s %s\n' "${object%%.*}" "$seed" "$mode" "$deg" "$mm" "$adds" \
        "$seconds" | tee -a "$rows"
    done
  done
done
python3 - "$rows" "$jitter" <<'PY'
import sys
rows = [l.split() for l in open(sys.argv[1]) if l.strip()]
LABELS = {"2": "2 views", "1": "1 view, depth searched"}


def line(label, sel):
    ok = lambda r, f: r[3] != "nan" and f(r)
    strict = sum(ok(r, lambda r: float(r[3]) <= 5 and float(r[4]) <= 10) for r in sel)
    adds = sum(ok(r, lambda r: float(r[5]) < 0.1) for r in sel)
    n = max(1, len(sel))
    mean_s = sum(float(r[6]) for r in sel) / n
    return "| %s | %d | %d (%.0f %%) | %d (%.0f %%) | %.1f |" % (
        label, len(sel), strict, 100.0 * strict / n, adds, 100.0 * adds / n, mean_s)


print()
print("| clicks (±%s px) | inits | within 5° / 10 mm | ADD-S < 0.1 d | mean time per init (s) |"
      % sys.argv[2])
print("|---|---:|---:|---:|---:|")
for mode in ("2", "1"):
    print(line(LABELS[mode], [r for r in rows if r[2] == mode]))
print()
print("| mesh, clicks | inits | within 5° / 10 mm | ADD-S < 0.1 d | mean time per init (s) |")
print("|---|---:|---:|---:|---:|")
for mesh in dict.fromkeys(r[0] for r in rows):
    for mode in ("2", "1"):
        print(line("%s, %s" % (mesh, LABELS[mode]), [r for r in rows if r[0] == mesh and r[2] == mode]))
PY
