#!/usr/bin/env bash
# Where the edge stage's measurement puts the image edge relative to the true contour, per rim
# direction (tests/bench/edge_bias_probe.cc; issue 12): on a `bcot synth` demo sequence and on
# the physically based renders cached under out/pbr/ by scripts/bench_pbr.sh or
# scripts/bench_quality.sh --pbr (those that exist).
#   scripts/bench_edge_bias.sh [--set edge.key=value ...]
# Environment: BCOT_BENCH_BUILD (an existing Release build with benchmarks; default build-bench,
# configured here), BCOT_BENCH_WORK (default out/bench_edge_bias).
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/bench_lib.sh
bench_build bcot edge_bias_probe
dir=$BENCH_DIR
work=${BCOT_BENCH_WORK:-out/bench_edge_bias}
if [ ! -f "$work/demo/rig.yaml" ]; then
  "$dir/bcot" synth --quiet --config configs/synth/demo.yaml --out "$work/demo" \
    --set motion.num_frames=20
fi
for seq in "$work/demo" out/pbr/*; do
  [ -f "$seq/gt/rig_from_object.txt" ] || continue
  echo "== $seq"
  "$dir/tests/bench/edge_bias_probe" --sequence "$seq" --config configs/annotate.yaml "$@"
done
