#!/usr/bin/env bash
# CTest `pbr_gt_check` (label pbr; registered only when Blender is found at configure time):
# renders configs/pbr/tiny_gt_check.json with scripts/pbr_synth.sh into a fresh directory and
# runs pbr_gt_check on it with a 0.05 px limit on the mean boundary distance per camera.
#   tests/bench/pbr_gt_check_test.sh SOURCE_DIR PBR_GT_CHECK_BINARY WORK_DIR
set -euo pipefail
src=$1 check=$2 work=$3
rm -rf "$work" "$work.partial"
mkdir -p "$(dirname "$work")"
BCOT_PBR_THREADS=${BCOT_PBR_THREADS:-2} "$src/scripts/pbr_synth.sh" "$src/configs/pbr/tiny_gt_check.json" "$work"
"$check" "$work" --max-mean-px 0.05
