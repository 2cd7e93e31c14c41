#!/usr/bin/env bash
# Capture range of frame 0 (MultiViewTracker::Initialize): one-frame demo-scene sequences
# (configs/synth/demo.yaml, binocular 90°) whose init_pose.txt is perturbed by R° / T mm about
# the object's bounding-box centre (bcot synth's init.rotation_deg / init.translation_mm, a
# seeded random axis and direction), solved by window_bench (tests/bench/window_bench.cc, the
# annotation setting) with the bootstrap passes until convergence (default) and with at most
# two passes (the former fixed two). Prints the frame-0 error per start and seed: rotation (deg)
# and |x| / |y| / |z| of the bounding-box centre in the rig frame (mm).
#
# Usage: scripts/bench_init.sh [seeds, default 3]
# Environment: BCOT_BENCH_WORK (default out/bench_init).
set -euo pipefail
cd "$(dirname "$0")/.."
seeds=${1:-3}
work=${BCOT_BENCH_WORK:-out/bench_init}
dir=build-bench
cmake -S . -B "$dir" -G Ninja -DCMAKE_BUILD_TYPE=Release -DBCOT_BUILD_TESTS=OFF \
  -DBCOT_BUILD_BENCHMARKS=ON >/dev/null
cmake --build "$dir" --target bcot window_bench >/dev/null
mkdir -p "$work"
starts=("5 10" "10 20" "15 30" "20 40" "30 50")
sequences=()
for start in "${starts[@]}"; do
  read -r deg mm <<<"$start"
  for seed in $(seq 1 "$seeds"); do
    seq_dir="$work/init_${deg}_${mm}_$seed"
    if [ ! -f "$seq_dir/rig.yaml" ]; then
      "$dir/bcot" synth --quiet --config configs/synth/demo.yaml --out "$seq_dir" \
        --set seed="$seed" --set motion.num_frames=1 --set init.rotation_deg="$deg" \
        --set init.translation_mm="$mm" >/dev/null 2>"$seq_dir.synth.log"
    fi
    sequences+=(--sequence "$seq_dir")
  done
done
# window_bench's per-frame row of each sequence: "| dir/name | per-frame | r | x | y | z | ...".
for passes in 8 2; do
  "$dir/tests/bench/window_bench" --config configs/annotate.yaml \
    --set tracker.bootstrap_passes=$passes "${sequences[@]}" 2>"$work/passes$passes.log" |
    awk -F' *\\| *' '$3 == "per-frame" { print $2, $4 "° / " $5 " / " $6 " / " $7 " mm" }' \
    >"$work/passes$passes.txt"
done
echo "| start | seed | frame 0, passes until converged | frame 0, at most two passes |"
echo "|---|---:|---|---|"
for start in "${starts[@]}"; do
  read -r deg mm <<<"$start"
  for seed in $(seq 1 "$seeds"); do
    name="$(basename "$work")/init_${deg}_${mm}_$seed"
    converged=$(awk -v n="$name" '$1 == n { $1 = ""; print substr($0, 2) }' "$work/passes8.txt")
    two=$(awk -v n="$name" '$1 == n { $1 = ""; print substr($0, 2) }' "$work/passes2.txt")
    echo "| ${deg}° / ${mm} mm | $seed | $converged | $two |"
  done
done
