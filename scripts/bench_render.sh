#!/usr/bin/env bash
# Render-layer benchmark: Release build in build-bench/, runs bench_render, prints Google
# Benchmark's console table, then a markdown summary (ms/frame, Mrays/s, Mrays/s per core).
# Usage: scripts/bench_render.sh [extra benchmark flags, e.g. --benchmark_filter=threads:1]
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/bench_lib.sh
run_google_benchmark bench_render "$@"

bench_summary bench_render <<'EOF'
import sys
import bench_json

report = bench_json.load(
    sys.argv[1],
    ["ms/frame is wall time per call; CPU ms is the calling thread's (with threads = 1 all work",
     "runs on it, so it is the single-core cost even when other processes share the CPU)."],
    ["benchmark", "threads", "rays or points", "ms/frame", "CPU ms", "Mrays/s", "Mrays/s/core"])
for b, ms, cpu_ms in bench_json.runs(report):
    threads = int(b["tbb_threads"])
    name = b["name"].rsplit("/threads:", 1)[0]
    if "rays_per_second" in b:
        mrays = b["rays_per_second"] / 1e6
        print(f"| {name} | {threads} | {int(b['rays'])} rays | {ms:.2f} | {cpu_ms:.2f} | "
              f"{mrays:.1f} | {mrays / threads:.1f} |")
    else:
        print(f"| {name} | {threads} | {int(b['points'])} points | {ms:.2f} | {cpu_ms:.2f} "
              f"| – | – |")
EOF
