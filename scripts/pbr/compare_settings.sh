#!/usr/bin/env bash
# Compares two annotation settings on the rendered sequences of SEQ_ROOT, the way
# docs/notes/issue12_evaluation_noise.md does: RUNS annotations per setting and sequence
# (scripts/pbr/annotate_seeds.sh: starts 0.1 % of a frame's motion apart), on the sequences as
# rendered and on copies with every second frame (twice the motion per frame,
# tests/bench/subsample_sequence.py), then scripts/pbr/compare_annotations.py on each set: per
# scene and over all, rotation, |t| and |bias y| of both settings, their difference and its
# standard error.
#
# Usage: scripts/pbr/compare_settings.sh [--seq-root out/pbr] [--out out/compare_settings]
#            [--runs 4] [--config configs/annotate.yaml] --a "OPTIONS" --b "OPTIONS"
#   OPTIONS: `bcot annotate` options of that setting, split at spaces ("" = the config as it is),
#   e.g. --a "" --b "--set edge.iterations=50". Annotations are kept under OUT/<a|b>/ and a rerun
#   with the same OUT resumes them (`bcot batch` skips a sequence whose DONE matches its config
#   and options, so other options in the same OUT are annotated anew).
# Environment: BCOT (default build/bcot), BCOT_PBR_ERRORS (default build/tests/bench/pbr_errors).
# Needs numpy (scripts/setup.sh --with-blender).
set -euo pipefail
cd "$(dirname "$0")/../.."
seq_root=out/pbr out=out/compare_settings runs=4 config=configs/annotate.yaml
have_a=0 have_b=0 options_a="" options_b=""
while [ $# -gt 0 ]; do
  case "$1" in
    --seq-root) seq_root=$2; shift 2 ;;
    --out) out=$2; shift 2 ;;
    --runs) runs=$2; shift 2 ;;
    --config) config=$2; shift 2 ;;
    --a) options_a=$2; have_a=1; shift 2 ;;
    --b) options_b=$2; have_b=1; shift 2 ;;
    *) echo "compare_settings: unknown argument '$1' (see the header of $0)" >&2; exit 2 ;;
  esac
done
if [ "$have_a" -eq 0 ] || [ "$have_b" -eq 0 ]; then
  echo "compare_settings: --a and --b are required (\"\" for the config as it is)" >&2
  exit 2
fi
[ -d "$seq_root" ] || { echo "compare_settings: $seq_root is not a directory" >&2; exit 2; }
pbr_errors=${BCOT_PBR_ERRORS:-build/tests/bench/pbr_errors}
[ -x "$pbr_errors" ] || { echo "compare_settings: $pbr_errors not built (scripts/build.sh)" >&2; exit 2; }

# The sets compared: the sequences as rendered, and copies with every second frame, made once.
every2="$out/every2"
declare -A roots=([full]=$seq_root [every2]=$every2)
mkdir -p "$every2"
for dir in "$seq_root"/*/; do
  dir=${dir%/}
  [ -f "$dir/rig.yaml" ] && [ -f "$dir/gt/rig_from_object.txt" ] || continue
  name=$(basename "$dir")
  [ -d "$every2/$name" ] && continue
  /usr/bin/python3 tests/bench/subsample_sequence.py "$dir" "$every2/$name.partial" 2 >/dev/null
  mv "$every2/$name.partial" "$every2/$name"
done

for side in a b; do
  options_var=options_$side
  read -ra options <<<"${!options_var}"
  for set in full every2; do
    scripts/pbr/annotate_seeds.sh "${roots[$set]}" "$out/$side/$set" "$runs" "$config" \
      "${options[@]}"
  done
done

for set in full every2; do
  echo
  echo "== $set: A = '$options_a', B = '$options_b' ($runs runs each, $config)"
  /usr/bin/python3 scripts/pbr/compare_annotations.py --pbr-errors "$pbr_errors" "${roots[$set]}" \
    --a "$out"/a/"$set"/v* --b "$out"/b/"$set"/v*
done
