#!/usr/bin/env bash
# Precision benchmark of the joint solver, the paper's Table 3 protocol on `bcot synth` data
# (tests/bench/precision_bench.cc): object moves freely with fixed cameras, C-0 alone and
# C-0 + C-k for the arc (5…120°) and cone (5…45°) cameras, errors in C-0's frame, lost frames
# (> 5° or > 50 mm) reset to ground truth; the paper's numbers in the row below ours.
# Then single-thread speed: two views at 640×480 with the tracking setting, and the 90° pair at
# 1280×1024 with the annotation setting.
#
# Usage: scripts/bench_precision.sh [frames per object, default 100]
# Environment: BCOT_BENCH_WORK (sequence cache, default out/bench_precision),
#              BCOT_BENCH_OBJECTS (comma-separated meshes; default 3 bundled + shared ones).
set -euo pipefail
cd "$(dirname "$0")/.."
frames=${1:-100}
work=${BCOT_BENCH_WORK:-out/bench_precision}
dir=build-bench
cmake -S . -B "$dir" -G Ninja -DCMAKE_BUILD_TYPE=Release -DBCOT_BUILD_TESTS=OFF \
  -DBCOT_BUILD_BENCHMARKS=ON >/dev/null
cmake --build "$dir" --target precision_bench
bench="$dir/tests/bench/precision_bench"

objects=${BCOT_BENCH_OBJECTS:-}
if [ -z "$objects" ]; then
  objects="data/meshes/bunny.obj,data/meshes/spool.off,data/meshes/pinion.off"
  for extra in ../shared/data/meshes/squirrel_demo_low.obj ../shared/data/meshes/dragknob.off; do
    if [ -f "$extra" ]; then objects="$objects,$extra"; fi
  done
fi
mkdir -p "$work"

echo "== Table 3 protocol, 640x480, annotation setting (configs/annotate.yaml)"
"$bench" --config configs/annotate.yaml --work "$work" --frames "$frames" --objects "$objects"

echo
echo "== Speed: C-0/C-7 (90°), 640x480, tracking setting (configs/track.yaml), one thread"
"$bench" --config configs/track.yaml --work "$work" --frames "$frames" --objects "$objects" \
  --settings C-0/C-7

echo
echo "== C-0 and C-0 + 90° camera at 1280x1024, annotation setting, one thread"
"$bench" --config configs/annotate.yaml --work "$work" --frames "$((frames < 30 ? frames : 30))" \
  --objects "$objects" --settings C-0,C-0/C-1 \
  --synth-set cameras.width=1280 --synth-set cameras.height=1024 \
  --synth-set "cameras.arc_angles_deg=[90]" --synth-set "cameras.cone_angles_deg=[]"
