#!/usr/bin/env bash
# Tracking-loop benchmark: Release build in build-bench/, runs bench_track (MultiViewTracker::
# Track, two views 640×480, one TBB thread, tracking and annotation settings), prints Google
# Benchmark's console table, then a markdown summary (ms/frame wall and CPU, frames/s).
# Usage: scripts/bench_track.sh [extra benchmark flags, e.g. --benchmark_repetitions=3]
set -euo pipefail
cd "$(dirname "$0")/.."
dir=build-bench
json="$dir/bench_track.json"
cmake -S . -B "$dir" -G Ninja -DCMAKE_BUILD_TYPE=Release \
  -DBCOT_BUILD_BENCHMARKS=ON >/dev/null
cmake --build "$dir" --target bench_track
# One run gives both outputs: the console table on stdout, JSON into a file.
"$dir/tests/bench/bench_track" --benchmark_format=console \
  --benchmark_out="$json" --benchmark_out_format=json "$@"

python3 - "$json" <<'PY'
import json, sys

with open(sys.argv[1]) as f:
    report = json.load(f)
ctx = report["context"]
print()
print(f"bcot Release build, {ctx.get('num_cpus', '?')} CPUs @ {ctx.get('mhz_per_cpu', '?')} MHz, "
      f"load average {ctx.get('load_avg', '?')}")
print("ms/frame is wall time per Track call; CPU ms is the calling thread's (TBB limited to one")
print("thread, so all work runs on it: the single-core cost even when other processes share the CPU).")
print()
print("| benchmark | frames | ms/frame | CPU ms/frame | frames/s (CPU) |")
print("|---|---:|---:|---:|---:|")
scale = {"ns": 1e-6, "us": 1e-3, "ms": 1.0, "s": 1e3}
for b in report["benchmarks"]:
    if b.get("run_type") == "aggregate" and b.get("aggregate_name") != "median":
        continue
    ms = b["real_time"] * scale[b["time_unit"]]
    cpu_ms = b["cpu_time"] * scale[b["time_unit"]]
    name = b["name"].split("/min_time")[0]
    print(f"| {name} | {int(b['frames'])} | {ms:.1f} | {cpu_ms:.1f} | {1000.0 / cpu_ms:.0f} |")
PY
