#!/usr/bin/env bash
# Annotates every rendered sequence of SEQ_ROOT once per start perturbation, for
# scripts/pbr/compare_annotations.py: run k uses `--set tracker.velocity_prediction=V_k`
# (1, 0.999, 0.998, ...: each frame starts 0.1 % of the last motion nearer the last pose), which
# changes nothing systematically but lets the tracking take another path through the frames.
# The spread between such runs is the noise floor of a comparison of two settings
# (docs/notes/issue12_evaluation_noise.md). The options under test therefore must not set
# tracker.velocity_prediction themselves (refused; compare such a setting with single runs).
#
# Usage: scripts/pbr/annotate_seeds.sh SEQ_ROOT OUT_ROOT RUNS CONFIG [bcot annotate options...]
#   writes OUT_ROOT/v<V>/<scene> per run and scene (<scene>: the sequence's name without the
#   `-<hash>` suffix scripts/pbr_synth.sh gives it; its messages in <scene>.log beside it), two
#   annotations at a time. A finished annotation is kept, so an interrupted run resumes.
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
[ -f "$config" ] || { echo "annotate_seeds: config $config does not exist" >&2; exit 2; }
for option in "$@"; do
  if [[ "$option" == *tracker.velocity_prediction* ]]; then
    echo "annotate_seeds: '$option': the runs differ by tracker.velocity_prediction, so the" \
      "options under test cannot set it" >&2
    exit 2
  fi
done

sequences=()
for dir in "$seq_root"/*/; do
  [ -f "$dir/rig.yaml" ] && [ -f "$dir/gt/rig_from_object.txt" ] && sequences+=("${dir%/}")
done
if [ ${#sequences[@]} -eq 0 ]; then
  echo "annotate_seeds: no rendered sequence with ground truth in $seq_root" >&2
  exit 2
fi

annotate() {  # sequence, velocity_prediction, extra options...
  local sequence=$1 v=$2
  shift 2
  local scene out
  scene=$(basename "$sequence" | sed -E 's/-[0-9a-f]{12}$//')
  out="$out_root/v$v/$scene"
  [ -f "$out/rig_from_object.txt" ] && return 0  # finished before
  rm -rf "$out.partial"
  mkdir -p "$(dirname "$out")"
  # Exit 3: written, but rejected by the quality check; its poses count like any others here.
  local code=0
  "$bcot" annotate "$sequence" --out "$out.partial" --config "$config" --quiet \
    --set tracker.velocity_prediction="$v" "$@" >/dev/null 2>"$out.log" || code=$?
  if [ "$code" -ne 0 ] && [ "$code" -ne 3 ]; then
    echo "annotate_seeds: $sequence (velocity_prediction $v) failed (exit $code):" >&2
    cat "$out.log" >&2
    return 1
  fi
  rm -rf "$out"
  mv "$out.partial" "$out"
}

status=0
for ((k = 0; k < runs; k++)); do
  v=$(awk -v k="$k" 'BEGIN { printf "%.3f", 1 - 0.001 * k }')
  pids=()
  for sequence in "${sequences[@]}"; do
    annotate "$sequence" "$v" "$@" &
    pids+=($!)
    if [ ${#pids[@]} -ge 2 ]; then
      wait "${pids[0]}" || status=1
      pids=("${pids[@]:1}")
    fi
  done
  for pid in "${pids[@]}"; do wait "$pid" || status=1; done
done
[ $status -eq 0 ] || { echo "annotate_seeds: an annotation failed" >&2; exit 1; }
echo "annotate_seeds: $runs run(s) of ${#sequences[@]} sequence(s) in $out_root/v*"
