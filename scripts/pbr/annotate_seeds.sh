#!/usr/bin/env bash
# Annotates every sequence under SEQ_ROOT once per start perturbation, for
# scripts/pbr/compare_annotations.py: run k is `bcot batch` with `--set
# tracker.velocity_prediction=V_k` (1, 0.999, 0.998, ...: each frame starts 0.1 % of the last
# motion nearer the last pose), which changes nothing systematically but lets the tracking take
# another path through the frames. The spread between such runs is the noise floor of a
# comparison of two settings (docs/notes/issue12_evaluation_noise.md). The options under test
# therefore must not set tracker.velocity_prediction themselves (refused; compare such a setting
# with single runs).
#
# Usage: scripts/pbr/annotate_seeds.sh SEQ_ROOT OUT_ROOT RUNS CONFIG [bcot annotate options...]
#   run k writes OUT_ROOT/v<V_k>/ as `bcot batch` does (the input tree mirrored, two sequences at
#   a time, resumable). An annotation the quality check rejects (exit 3) is a result here too.
# Environment: BCOT (default build/bcot).
set -euo pipefail
cd "$(dirname "$0")/../.."
if [ $# -lt 4 ]; then
  echo "usage: scripts/pbr/annotate_seeds.sh SEQ_ROOT OUT_ROOT RUNS CONFIG [options...]" >&2
  exit 2
fi
seq_root=$1 out_root=$2 runs=$3 config=$4
shift 4
bcot=${BCOT:-build/bcot}
if ! [[ "$runs" =~ ^[1-9][0-9]*$ ]] || [ "$runs" -gt 100 ]; then
  echo "annotate_seeds: RUNS must be 1..100, got '$runs'" >&2
  exit 2
fi
[ -x "$bcot" ] || { echo "annotate_seeds: $bcot is not an executable (set BCOT)" >&2; exit 2; }
for option in "$@"; do
  if [[ "$option" == *tracker.velocity_prediction* ]]; then
    echo "annotate_seeds: '$option': the runs differ by tracker.velocity_prediction, so the" \
      "options under test cannot set it" >&2
    exit 2
  fi
done

for ((k = 0; k < runs; k++)); do
  v=$(awk -v k="$k" 'BEGIN { printf "%.3f", 1 - 0.001 * k }')
  code=0
  "$bcot" batch "$seq_root" --out "$out_root/v$v" --jobs 2 --config "$config" --quiet \
    "$@" --set tracker.velocity_prediction="$v" || code=$?
  if [ "$code" -ne 0 ] && [ "$code" -ne 3 ]; then
    echo "annotate_seeds: run $k (velocity_prediction $v) failed (exit $code)" >&2
    exit 1
  fi
done
echo "annotate_seeds: $runs run(s) in $out_root/v*"
