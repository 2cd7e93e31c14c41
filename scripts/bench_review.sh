#!/usr/bin/env bash
# Review workbench benchmark (issue 16): the server-side cost of a frame switch, i.e. the view
# images the page requests for the next frame (read, cast the annotated silhouette with Embree,
# draw its contour, encode JPEG), for two 960×768 views and for one (tests/bench/bench_review.cc).
# Release build in build-bench/; prints Google Benchmark's console table, then a markdown
# summary. Target: ≤ 150 ms per frame switch of two views.
# Usage: scripts/bench_review.sh [extra benchmark flags]
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/bench_lib.sh
run_google_benchmark bench_review "$@"

bench_summary bench_review <<'PY'
import sys
import bench_json

report = bench_json.load(
    sys.argv[1],
    ["ms per frame switch is wall time per call; views are served one after the other here (the",
     "server answers the page's requests on several threads, so this is the single-core cost)."],
    ["views", "image size", "ms per frame switch", "CPU ms", "JPEG KiB per view", "target"])
for b, ms, cpu_ms in bench_json.runs(report):
    views = int(b["views"])
    target = "≤ 150 ms" if views == 2 else "–"
    print(f"| {views} | {int(b['width'])}×{int(b['height'])} | {ms:.1f} | {cpu_ms:.1f} | "
          f"{b['jpeg_kb_per_view']:.0f} | {target} |")
PY
