#!/usr/bin/env bash
# Edge-fit benchmark: Release build in build-bench/, runs bench_edge_fit (FitEdgeProfile, the
# blurred-step fit of the edge stage and the quality check, on 2,000 seeded profiles), prints
# Google Benchmark's console table, then a markdown summary (µs per fit, fraction found, mean
# |μ − truth| of the found step fits).
# Usage: scripts/bench_edge_fit.sh [extra benchmark flags, e.g. --benchmark_repetitions=3]
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/bench_lib.sh
run_google_benchmark bench_edge_fit "$@"

bench_summary bench_edge_fit <<'PY'
import sys
import bench_json

report = bench_json.load(
    sys.argv[1],
    ["µs/fit is CPU time per FitEdgeProfile call over the 2,000 profiles (one thread)."],
    ["benchmark", "µs/fit", "fits/s", "found", "mean |μ error| (px)"])
for b, ms, cpu_ms in bench_json.runs(report, aggregate="median"):
    per_fit_us = 1000.0 * cpu_ms / 2000
    print(f"| {b['name']} | {per_fit_us:.2f} | {b['items_per_second']:.0f} | "
          f"{b['found_fraction']:.3f} | {b['mean_abs_error_px']:.4f} |")
PY
