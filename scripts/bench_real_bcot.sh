#!/usr/bin/env bash
# Real-data check: tracks ../shared/data/bcot_real_cat monocularly (frames 1..30 from the
# frame-0 ground truth, reset only after a 5°/5 cm failure) and prints the error of every frame
# against BCOT's own annotation, then the 5°5cm / 2°2cm success rates
# (tests/bench/real_bcot_bench.cc). Runs the tracking and the annotation setting, each with
# every region energy (cost.energy = dense, sparse, combined). Then the same frames solved
# each from its own annotation (--from-truth, annotation setting): how far the image optimum
# lies from BCOT's annotation, i.e. the part of the error that is disagreement, not drift.
# Usage: scripts/bench_real_bcot.sh [data dir, default ../shared/data/bcot_real_cat]
set -euo pipefail
cd "$(dirname "$0")/.."
data=${1:-../shared/data/bcot_real_cat}
if [ ! -d "$data/handheld_demo/Cat" ]; then
  echo "bench_real_bcot: $data/handheld_demo/Cat not found" >&2
  exit 1
fi
dir=build-bench
cmake -S . -B "$dir" -G Ninja -DCMAKE_BUILD_TYPE=Release -DBCOT_BUILD_TESTS=OFF \
  -DBCOT_BUILD_BENCHMARKS=ON >/dev/null
cmake --build "$dir" --target real_bcot_bench
for config in configs/track.yaml configs/annotate.yaml; do
  for energy in dense sparse combined; do
    echo "== $config, cost.energy=$energy"
    "$dir/tests/bench/real_bcot_bench" --scene "$data/handheld_demo" --object Cat \
      --model "$data/models/Cat.obj" --config "$config" --set "cost.energy=$energy"
    echo
  done
done
echo "== configs/annotate.yaml, every frame solved from its own annotation (--from-truth)"
"$dir/tests/bench/real_bcot_bench" --scene "$data/handheld_demo" --object Cat \
  --model "$data/models/Cat.obj" --config configs/annotate.yaml --from-truth
