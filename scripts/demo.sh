#!/usr/bin/env bash
# The main job on bundled demo data, from a fresh clone: install packages, build, synthesize a
# binocular 90° sequence (one cluttered and one plain background) with ground truth, annotate
# it with `bcot batch` and the annotation setting (configs/annotate.yaml), and check each
# annotation's reprojection error (quality report, accept / reject).
# Output: out/demo/sequences/binocular (the input contract of docs/architecture.md, plus gt/) and
# out/demo/annotations (the output contract: poses, quality.json, report.html, DONE; plus
# summary.json / summary.html over the batch). Rerunning skips finished sequences.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
scripts/build.sh release
out=${1:-out/demo}
if [ ! -f "$out/sequences/binocular/rig.yaml" ]; then
  ./build/bcot synth --config configs/synth/demo.yaml --out "$out/sequences/binocular"
fi
status=0
./build/bcot batch "$out/sequences" --out "$out/annotations" --config configs/annotate.yaml \
  || status=$?
./build/bcot report "$out/annotations" || status=$?
echo "demo: sequences in $out/sequences, annotations in $out/annotations"
echo "demo: summary: $(cd "$out/annotations" && pwd)/summary.html"
exit $status
