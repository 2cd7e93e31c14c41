#!/usr/bin/env bash
# Edge-fit benchmark: Release build in build-bench/, runs bench_edge_fit, prints Google
# Benchmark's console table, then a markdown summary (µs per fit or line, fraction found, mean
# signed and absolute μ error) of:
#   FitEdgeProfile                the blurred-step fit of the edge stage and the quality check,
#                                 on 2,000 seeded profiles;
#   FitEdgeAcross_Uncorrected / _Jpeg420   1,000 lines across JPEG 4:2:0 colour edges, measured
#                                 as full-resolution colour and with the chroma shift taken off.
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
    ["µs is CPU time per FitEdgeProfile call, resp. per FitEdgeAcross line (one thread)."],
    ["benchmark", "µs each", "per second", "found", "mean μ error (px)", r"mean \|μ error\| (px)"])
for b, ms, cpu_ms in bench_json.runs(report, aggregate="median"):
    per_item_us = 1e6 / b["items_per_second"]
    signed = b.get("mean_error_px")
    signed = f"{signed:+.4f}" if signed is not None else "–"
    print(f"| {b['name']} | {per_item_us:.2f} | {b['items_per_second']:.0f} | "
          f"{b['found_fraction']:.3f} | {signed} | {b['mean_abs_error_px']:.4f} |")
PY
