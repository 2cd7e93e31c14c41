#!/usr/bin/env bash
# Reading one 960×768 JPEG frame: bcot's ReadColorImage against cv::imread / cv::imdecode
# (tests/bench/bench_image_read.cc; one thread). Prints Google Benchmark's console table, then a
# markdown summary.
# Usage: scripts/bench_image_read.sh [extra benchmark flags, e.g. --benchmark_repetitions=3]
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/bench_lib.sh
run_google_benchmark bench_image_read "$@"

bench_summary bench_image_read <<'PY'
import sys
import bench_json

report = bench_json.load(sys.argv[1], ["One 960×768 JPEG (quality 90, 4:2:0) per call."],
                         ["benchmark", "ms per image", "CPU ms"])
for b, ms, cpu_ms in bench_json.runs(report):
    print(f"| {b['name']} | {ms:.2f} | {cpu_ms:.2f} |")
PY
