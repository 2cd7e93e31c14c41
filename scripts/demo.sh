#!/usr/bin/env bash
# The main job on bundled demo data, from a fresh clone: install packages, build, synthesize a
# binocular 90° sequence (one cluttered and one plain background) with ground truth, annotate
# it with the annotation setting (configs/annotate.yaml).
# Output: out/demo/sequence (the input contract of DESIGN.md, plus gt/) and out/demo/annotation
# (the output contract).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
scripts/build.sh release
out=${1:-out/demo}
rm -rf "$out/sequence"
./build/bcot synth --config configs/synth/demo.yaml --out "$out/sequence"
./build/bcot annotate "$out/sequence" --out "$out/annotation" --config configs/annotate.yaml
echo "demo: synthetic sequence in $out/sequence, annotation in $out/annotation"
