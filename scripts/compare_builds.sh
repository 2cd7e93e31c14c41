#!/usr/bin/env bash
# Checks that two bcot builds annotate identically (for refactorings that must not change
# results): synthesizes the demo sequence and 20 frames of glossy_fast with the first build,
# annotates both with configs/annotate.yaml (bcot batch) and the demo with configs/track.yaml
# using each build, and compares rig_from_object.txt, <camera>/pose.txt, quality.csv and
# frames.csv (without its wall-time column) byte for byte.
# Usage: scripts/compare_builds.sh BCOT_BEFORE BCOT_AFTER [work dir, default out/compare_builds]
# Environment: BCOT_CONFIGS_BEFORE, BCOT_CONFIGS_AFTER: the configs/ folder each build reads
# (default configs/; an older build may not know a newer config's sections, e.g.
# `git archive REV configs | tar -x -C /tmp/old` gives the configs of revision REV).
set -euo pipefail
cd "$(dirname "$0")/.."
if [ $# -lt 2 ]; then
  echo "usage: scripts/compare_builds.sh BCOT_BEFORE BCOT_AFTER [work dir]" >&2
  exit 2
fi
before=$(realpath "$1")
after=$(realpath "$2")
work=${3:-out/compare_builds}
mkdir -p "$work/seq"
# Each sequence is synthesized beside its final name and renamed when complete, so an
# interrupted run never leaves a partial sequence that a rerun would take as finished.
synth() {  # name, config, extra synth arguments...
  local name=$1 config=$2
  shift 2
  [ -d "$work/seq/$name" ] && return 0
  rm -rf "$work/seq-partial/$name"
  "$before" synth --config "$config" --out "$work/seq-partial/$name" "$@" >/dev/null
  mv "$work/seq-partial/$name" "$work/seq/$name"
}
synth demo configs/synth/demo.yaml
synth glossy configs/synth/glossy_fast.yaml --set motion.num_frames=20
configs_before=${BCOT_CONFIGS_BEFORE:-configs}
configs_after=${BCOT_CONFIGS_AFTER:-configs}
for side in before after; do
  bin=${!side}
  configs_var=configs_$side
  configs=${!configs_var}
  rm -rf "${work:?}/$side"
  "$bin" batch "$work/seq" --out "$work/$side/ann" --config "$configs/annotate.yaml" --jobs 1 \
    >/dev/null 2>&1 || true  # a rejected sequence exits 3, a failed one 1; the files are compared below
  "$bin" annotate "$work/seq/demo" --out "$work/$side/track" --config "$configs/track.yaml" \
    --quiet 2>/dev/null || true
done
status=0
for dir in ann/demo ann/glossy track; do
  for file in rig_from_object.txt cam0/pose.txt cam1/pose.txt quality.csv; do
    if [ -f "$work/before/$dir/$file" ] && cmp -s "$work/before/$dir/$file" "$work/after/$dir/$file"; then
      echo "same       $dir/$file"
    else
      echo "DIFFERENT  $dir/$file"; status=1
    fi
  done
  # frames.csv without the milliseconds column (wall time).
  strip() { python3 -c 'import csv,sys
rows=list(csv.reader(open(sys.argv[1])))
i=rows[0].index("milliseconds")
print("\n".join(",".join(r[:i]+r[i+1:]) for r in rows))' "$1"; }
  if [ -f "$work/before/$dir/frames.csv" ] && [ -f "$work/after/$dir/frames.csv" ] &&
    [ "$(strip "$work/before/$dir/frames.csv")" = "$(strip "$work/after/$dir/frames.csv")" ]; then
    echo "same       $dir/frames.csv (wall time excluded)"
  else
    echo "DIFFERENT  $dir/frames.csv"; status=1
  fi
done
exit $status
