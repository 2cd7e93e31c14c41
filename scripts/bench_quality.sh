#!/usr/bin/env bash
# Honesty check of the quality report (tests/bench/quality_bench.cc): the measured reprojection
# error (contour of a pose vs the boundary found in the image) beside the true projected contour
# error computed from ground truth, per frame and view, and per pose set: rows, frame-views that
# cannot be told, Pearson correlation, mean |measured − true| p90, the share within 0.5 px, mean
# measured/true p90 (where true >= 0.5 px) and the verdict. Pose sets: the annotation
# (configs/annotate.yaml), ground truth, ground truth shifted 1, 2 and 3 px in cam0's image,
# rotated about cam0's axis so the contour moves up to 1 and 3 px, and (demo, glossy_fast)
# ground truth perturbed per frame by a seeded random rigid motion of up to 1.5° / 4 mm.
# Sequences: bcot synth's demo, glossy_fast and a spool with shaded rims (spool_rim), and with
# --pbr three Cycles renders.
#
# Usage: scripts/bench_quality.sh [frames per synthetic sequence, default 20] [--pbr]
#          [--set key=value ...]
#   --pbr   also the physically based sequences of configs/pbr/ (bunny_plastic,
#           pinion_metal_moving_light, spool_dark; rendered with Blender as in
#           scripts/bench_pbr.sh, cached under out/pbr/; needs scripts/setup.sh --with-blender)
#   --set   quality options for the measurement, e.g. --set quality.refine_on_edges=false
#           --set quality.fit_scale_px=1 (the colour-posterior boundary before issue 18).
# Environment: BCOT_BENCH_WORK (default out/bench_quality), BCOT_BENCH_BUILD (an existing
# Release build directory configured with -DBCOT_BUILD_BENCHMARKS=ON, used as it is; default:
# build-bench, configured here).
set -euo pipefail
cd "$(dirname "$0")/.."
frames=20
if [[ $# -gt 0 && $1 =~ ^[0-9]+$ ]]; then frames=$1; shift; fi
pbr=0
sets=()
while [ $# -gt 0 ]; do
  case "$1" in
    --pbr) pbr=1; shift ;;
    --set) sets+=(--set "$2"); shift 2 ;;
    *) echo "bench_quality: unknown argument $1" >&2; exit 2 ;;
  esac
done
work=${BCOT_BENCH_WORK:-out/bench_quality}
source scripts/bench_lib.sh
bench_build bcot quality_bench
dir=$BENCH_DIR
mkdir -p "$work"
names=() seqs=() extra=()
for name in demo glossy_fast; do
  seq="$work/$name"
  if [ ! -f "$seq/rig.yaml" ]; then
    "$dir/bcot" synth --quiet --config "configs/synth/$name.yaml" --out "$seq" \
      --set motion.num_frames="$frames"
  fi
  names+=("$name") seqs+=("$seq") extra+=("--perturbed --seed 1")
done
# The spool of scripts/bench_throughput.sh (shaded rims, seed 23): its flanges' rims are creases
# a few px inside the silhouette where the flange's side has little contrast against the
# background (quality step 4b, docs/quality.md).
seq="$work/spool_rim"
if [ ! -f "$seq/rig.yaml" ]; then
  "$dir/bcot" synth --quiet --config configs/synth/shaded_rim.yaml --out "$seq" --set seed=23 \
    --set object.mesh="$PWD/data/meshes/spool.off" --set motion.num_frames="$frames"
fi
names+=(spool_rim) seqs+=("$seq") extra+=("")
if [ "$pbr" = 1 ]; then
  for spec in configs/pbr/bunny_plastic.json configs/pbr/pinion_metal_moving_light.json \
              configs/pbr/spool_dark.json; do
    key=$(/usr/bin/python3 scripts/pbr/spec_key.py "$spec")
    seq=out/pbr/$key
    if [ ! -d "$seq" ]; then
      echo "bench_quality: rendering $seq" >&2
      scripts/pbr_synth.sh "$spec" "$seq" >&2
    fi
    names+=("$key") seqs+=("$seq") extra+=("")
  done
fi
summary="$work/summary.txt"
: >"$summary"
for i in "${!names[@]}"; do
  name=${names[$i]} seq=${seqs[$i]}
  ann="$work/$name.annotation"
  rm -rf "$ann"
  # Exit 3 (written, rejected by the quality check) is an outcome this bench measures.
  "$dir/bcot" annotate --quiet "$seq" --out "$ann" --config configs/annotate.yaml || [ $? -eq 3 ]
  read -r -a more <<<"${extra[$i]}"
  "$dir/tests/bench/quality_bench" --sequence "$seq" --config configs/annotate.yaml \
    --poses "$ann/rig_from_object.txt" "${more[@]}" --offset-px 1 --offset-px 2 --offset-px 3 \
    --rotate-px 1 --rotate-px 3 "${sets[@]}" >"$work/$name.rows.txt"
  { echo "== $name"; grep -E " rows | verdict: " "$work/$name.rows.txt"; } | tee -a "$summary"
done
echo "bench_quality: per frame-view rows in $work/<name>.rows.txt, this summary in $summary"
