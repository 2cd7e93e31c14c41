#!/usr/bin/env bash
# The main job on bundled demo data, from a fresh clone: install packages, build, synthesize a
# binocular 90° sequence (one cluttered and one plain background) with ground truth.
# Output: out/demo/sequence (the input contract of DESIGN.md, plus gt/).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
scripts/build.sh release
out=${1:-out/demo}
rm -rf "$out/sequence"
./build/bcot synth --config configs/synth/demo.yaml --out "$out/sequence"
echo "demo: synthetic sequence written to $out/sequence"
