#!/usr/bin/env bash
# Precision of bcot on physically based (Blender Cycles) renders, issue 12.
#   scripts/bench_pbr.sh [SPEC.json | SEQUENCE_DIR ...]
# A directory argument is a sequence rendered before (scripts/pbr_synth.sh SPEC DIR, with gt/):
# it is measured as it is, under its directory's name, and never rendered again.
# Default: the bench scenes of configs/pbr/ (bunny plastic, spool dark + JPEG, pinion metal
# with a moving key light + JPEG, large bright bunny in soft light + JPEG, small glossy and small
# diffuse bunny turning fast + JPEG, bunny turning 5–8° per frame with motion blur + JPEG, the
# plastic bunny with a thumb-sized occluder sweeping across it in cam0, the plastic bunny again as
# JPEG 90 4:2:0: a large saturated object in issue 12's hidden set's format) and the control
# bunny_plastic_light_below (the key light from below).
# For each scene spec: renders the sequence with scripts/pbr_synth.sh into out/pbr/<name>-<hash>
# (hash of the resolved spec and the generator's scripts; an existing render is reused), checks
# its ground truth (tests/bench/pbr_gt_check: Blender mask vs Embree, and the boundary contrast
# at the true contour), then annotates it three ways:
#   annotate   configs/annotate.yaml
#   track      configs/track.yaml
#   cam0       configs/annotate.yaml --set views.cameras=[cam0]
# and prints, per camera and averaged over cameras and sequences: mean / max rotation error (deg),
# mean |t| per camera axis (mm), mean signed error per axis (bias) and its standard deviation,
# worst ‖t‖, lost frames (> 5° or > 50 mm), CPU ms per frame (user + sys of `bcot annotate` / frames);
# errors in each camera's frame at the object's bounding-box centre (tests/bench/pbr_errors),
# plus the bias per 10-frame block for the annotate setting. Extra `bcot annotate` arguments:
# BCOT_PBR_ANNOTATE_ARGS (e.g. "--set solver.rounds=3"); BCOT_PBR_REUSE_ANN=1 keeps finished
# annotations (out/pbr/ann/<seq>/<setting>/DONE) instead of redoing them (only valid when
# neither bcot nor the arguments changed). BCOT_PBR_FRAME_STEP=N (> 1) measures every scene at
# 1/N of its frame rate instead: every N-th frame, copied once into <sequence>-every<N>
# (tests/bench/subsample_sequence.py; docs/notes/issue12_fast_motion.md).
# Needs scripts/setup.sh --with-blender.
set -euo pipefail
cd "$(dirname "$0")/.."
specs=("$@")
if [ ${#specs[@]} -eq 0 ]; then
  specs=(configs/pbr/bunny_plastic.json configs/pbr/spool_dark.json
         configs/pbr/pinion_metal_moving_light.json configs/pbr/bunny_bright_soft.json
         configs/pbr/bunny_plastic_light_below.json configs/pbr/bunny_small_glossy_fast.json
         configs/pbr/bunny_small_diffuse_fast.json configs/pbr/bunny_fast_blur.json
         configs/pbr/bunny_hand_occluder.json configs/pbr/bunny_plastic_jpeg.json)
fi
py=/usr/bin/python3
nice cmake --build build -j1 --target bcot pbr_errors pbr_gt_check >/dev/null
root=out/pbr
results=$root/results.tsv.partial
: >"$results"
checks=$root/gt_checks.txt
: >"$checks"
read -r -a extra <<<"${BCOT_PBR_ANNOTATE_ARGS:-}"
step=${BCOT_PBR_FRAME_STEP:-1}
[[ "$step" =~ ^[1-9][0-9]*$ ]] || { echo "bench_pbr: BCOT_PBR_FRAME_STEP=$step: must be an integer >= 1" >&2; exit 2; }
for spec in "${specs[@]}"; do
  if [ -d "$spec" ]; then
    [ -d "$spec/gt" ] || { echo "bench_pbr: $spec has no gt/ (not a rendered sequence)" >&2; exit 2; }
    seq=${spec%/}
    key=$(basename "$seq")
  else
    key=$($py scripts/pbr/spec_key.py "$spec")
    seq=$root/$key
    if [ ! -d "$seq" ]; then
      echo "bench_pbr: rendering $seq" >&2
      scripts/pbr_synth.sh "$spec" "$seq" >&2
    fi
  fi
  if [ "$step" -gt 1 ]; then
    if [ ! -d "$seq-every$step" ]; then
      $py tests/bench/subsample_sequence.py "$seq" "$seq-every$step.partial" "$step" >&2
      mv "$seq-every$step.partial" "$seq-every$step"
    fi
    seq=$seq-every$step
    key=$key-every$step
  fi
  frames=$(ls "$seq/cam0" | wc -l)
  { echo "== $key ($(cat "$seq/pbr_timing.json"))"; build/tests/bench/pbr_gt_check "$seq"; } >>"$checks"
  contrast=$(build/tests/bench/pbr_gt_check "$seq" --contrast-only | awk '$1 != "all" {print $1 "=" $NF}' | paste -sd' ')
  for variant in annotate track cam0; do
    case $variant in
      annotate) args=(--config configs/annotate.yaml) ;;
      track) args=(--config configs/track.yaml) ;;
      cam0) args=(--config configs/annotate.yaml --set 'views.cameras=[cam0]') ;;
    esac
    ann=$root/ann/$key/$variant
    if [ "${BCOT_PBR_REUSE_ANN:-0}" != 1 ] || [ ! -f "$ann/DONE" ] || [ ! -s "$ann.time" ]; then
      rm -rf "$ann"
      mkdir -p "$(dirname "$ann")"
      echo "bench_pbr: $key $variant" >&2
      TIMEFORMAT='%U %S'
      { time nice build/bcot annotate "$seq" --out "$ann" "${args[@]}" "${extra[@]}" >"$ann.log" 2>&1; } 2>"$ann.time" ||
        [ $? -eq 3 ] ||  # 3: written but rejected by the quality check; still measured
        { echo "bench_pbr: bcot annotate failed, see $ann.log" >&2; exit 1; }
    fi
    cpu_ms=$(awk -v n="$frames" '{printf "%.0f", ($1 + $2) * 1000 / n}' "$ann.time")
    blocks=()
    [ "$variant" = annotate ] && blocks=(--blocks 10)
    build/tests/bench/pbr_errors "$seq" "$ann" "${blocks[@]}" --rotation |
      awk -v s="$key" -v v="$variant" -v c="$cpu_ms" -v k="$contrast" 'BEGIN{OFS="\t"} {print s, v, c, k, $0}' >>"$results"
  done
done
mv "$results" "$root/results.tsv"
cat "$checks"
$py scripts/pbr/bench_table.py "$root/results.tsv"
