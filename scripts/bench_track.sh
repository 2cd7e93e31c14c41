#!/usr/bin/env bash
# Tracking-loop benchmark: Release build in build-bench/, runs bench_track (MultiViewTracker::
# Track, two views 640×480, one TBB thread, tracking and annotation settings), prints Google
# Benchmark's console table, then a markdown summary (ms/frame wall and CPU, frames/s).
# Usage: scripts/bench_track.sh [extra benchmark flags, e.g. --benchmark_repetitions=3]
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/bench_lib.sh
run_google_benchmark bench_track "$@"

bench_summary bench_track <<'PY'
import sys
import bench_json

report = bench_json.load(
    sys.argv[1],
    ["ms/frame is wall time per Track call; CPU ms is the calling thread's (TBB limited to one",
     "thread, so all work runs on it: the single-core cost even when other processes share it)."],
    ["benchmark", "frames", "ms/frame", "CPU ms/frame", "frames/s (CPU)"])
for b, ms, cpu_ms in bench_json.runs(report, aggregate="median"):
    name = b["name"].split("/min_time")[0]
    print(f"| {name} | {int(b['frames'])} | {ms:.1f} | {cpu_ms:.1f} | {1000.0 / cpu_ms:.0f} |")
PY
