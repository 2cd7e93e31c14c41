#!/usr/bin/env bash
# Render-layer benchmark: Release build in build-bench/, runs bench_render, prints Google
# Benchmark's console table, then a markdown summary (ms/frame, Mrays/s, Mrays/s per core).
# Usage: scripts/bench_render.sh [extra benchmark flags, e.g. --benchmark_filter=threads:1]
set -euo pipefail
cd "$(dirname "$0")/.."
dir=build-bench
json="$dir/bench_render.json"
cmake -S . -B "$dir" -G Ninja -DCMAKE_BUILD_TYPE=Release -DBCOT_BUILD_TESTS=OFF \
  -DBCOT_BUILD_BENCHMARKS=ON >/dev/null
cmake --build "$dir" --target bench_render
# One run gives both outputs: the console table on stdout, JSON into a file.
"$dir/tests/bench/bench_render" --benchmark_format=console \
  --benchmark_out="$json" --benchmark_out_format=json "$@"

python3 - "$json" <<'EOF'
import json, sys

with open(sys.argv[1]) as f:
    report = json.load(f)
ctx = report["context"]
print()
print(f"bcot Release build, {ctx.get('num_cpus', '?')} CPUs @ {ctx.get('mhz_per_cpu', '?')} MHz, "
      f"load average {ctx.get('load_avg', '?')}")
print("ms/frame is wall time per call; CPU ms is the calling thread's (with threads = 1 all work")
print("runs on it, so it is the single-core cost even when other processes share the CPU).")
print()
print("| benchmark | threads | rays or points | ms/frame | CPU ms | Mrays/s | Mrays/s/core |")
print("|---|---:|---:|---:|---:|---:|---:|")
scale = {"ns": 1e-6, "us": 1e-3, "ms": 1.0, "s": 1e3}
for b in report["benchmarks"]:
    if b.get("run_type") == "aggregate":
        continue
    ms = b["real_time"] * scale[b["time_unit"]]
    cpu_ms = b["cpu_time"] * scale[b["time_unit"]]
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
