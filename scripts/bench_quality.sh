#!/usr/bin/env bash
# Honesty check of the quality report (tests/bench/quality_bench.cc): on `bcot synth`
# sequences, the measured reprojection error (contour of a pose vs the boundary found in the
# image) beside the true projected contour error computed from ground truth, per frame and
# view, and their Pearson correlation (target >= 0.9). Poses: the real annotation of each
# sequence (tracking setting) and ground truth perturbed per frame by a seeded random rigid
# motion of up to 1.5° / 4 mm, so errors span 0 to a few px.
#
# Usage: scripts/bench_quality.sh [frames per sequence, default 20] [--set key=value ...]
#   e.g. --set quality.fit_rigid_motion=false --set quality.color_kind=global (raw offsets of a
#   global colour model, the measurement before the rigid motion fit).
# Environment: BCOT_BENCH_WORK (default out/bench_quality).
set -euo pipefail
cd "$(dirname "$0")/.."
frames=${1:-20}
shift $(( $# > 0 ? 1 : 0 ))
work=${BCOT_BENCH_WORK:-out/bench_quality}
dir=build-bench
cmake -S . -B "$dir" -G Ninja -DCMAKE_BUILD_TYPE=Release -DBCOT_BUILD_TESTS=OFF \
  -DBCOT_BUILD_BENCHMARKS=ON >/dev/null
cmake --build "$dir" --target bcot quality_bench
mkdir -p "$work"
for name in demo glossy_fast; do
  seq="$work/$name"
  if [ ! -f "$seq/rig.yaml" ]; then
    "$dir/bcot" synth --quiet --config "configs/synth/$name.yaml" --out "$seq" \
      --set motion.num_frames="$frames"
  fi
  "$dir/bcot" annotate --quiet "$seq" --out "$work/$name.annotation" --config configs/annotate.yaml
  echo "== $name: measured (report) vs true (ground truth) contour error, px"
  "$dir/tests/bench/quality_bench" --sequence "$seq" --config configs/annotate.yaml \
    --poses "$work/$name.annotation/rig_from_object.txt" --perturbed --seed 1 --offset-px 3 "$@"
done
