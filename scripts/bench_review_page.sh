#!/usr/bin/env bash
# Review workbench benchmark in the browser (issue 16): the frame switch of `bcot review`'s page
# end to end in headless Chromium — from the page's showFrame until every view's image has
# loaded: server work (image read, Embree contour, JPEG), transfer, decode and the redraw of the
# three charts (tests/bench/review_page_bench.py). A `bcot synth` sequence of two 960×768 views
# (configs/synth/demo.yaml, FRAMES frames, default 120), annotated with configs/track.yaml, served
# by `bcot review` on a free loopback port. Prints a markdown table. Target: ≤ 150 ms per switch.
# Usage: scripts/bench_review_page.sh [FRAMES [SWITCHES]]
# Environment: BCOT_BUILD (default build), BCOT_BENCH_WORK (default out/bench_review_page).
# Needs Chromium and Python 3 (scripts/setup.sh).
set -euo pipefail
cd "$(dirname "$0")/.."
frames=${1:-120}
switches=${2:-40}
build=${BCOT_BUILD:-build}
work=${BCOT_BENCH_WORK:-out/bench_review_page}
seq="$work/seq_${frames}"
if [ ! -f "$seq/gt/rig_from_object.txt" ]; then
  rm -rf "$seq"
  "$build/bcot" synth --quiet --config configs/synth/demo.yaml --out "$seq" \
    --set cameras.width=960 --set cameras.height=768 --set motion.num_frames="$frames"
fi
rm -rf "$work/ann"
"$build/bcot" annotate --quiet "$seq" --out "$work/ann" --config configs/track.yaml || [ $? -eq 3 ]
"$build/bcot" review "$seq" --annotation "$work/ann" --port 0 --quiet >"$work/url.txt" &
server=$!
trap 'kill $server 2>/dev/null || true' EXIT
for _ in $(seq 100); do [ -s "$work/url.txt" ] && break; sleep 0.1; done
url=$(head -1 "$work/url.txt")
python3 tests/bench/review_page_bench.py /usr/bin/chromium "$url" "$switches"
