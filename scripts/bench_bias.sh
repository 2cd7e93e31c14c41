#!/usr/bin/env bash
# Bias benchmark (tests/bench/bias_bench.cc): signed pose error per camera under shaded rims.
# `bcot synth` sequences from configs/synth/shaded_rim.yaml (binocular 90°, 960×768, f = 720 px,
# key light with a low ambient term, soft light, background tinted towards the object colour,
# 0.6 px blur, noise, JPEG 4:2:0), one per light direction × material; each tracked from the
# truth of frame 0 with every camera (the per-frame solve of `bcot annotate`). One table per
# solver setting: rows = light × material × camera; columns = boundary contrast at the true
# contour, mean rotation error, mean |t| per axis, mean signed t per axis ± its standard
# deviation (bias; camera axes: x right, y down, z forward; at the bounding-box centre), lost,
# CPU ms/frame. Then the evidence for the cause: signed contour offsets at the true pose of
# the region measurement and of the edge measurement by rim side (--evidence).
#
# Usage: scripts/bench_bias.sh [frames, default 20] [annotate config, default configs/annotate.yaml]
# Environment: BCOT_BENCH_WORK (sequence cache, default out/bench_bias),
#              BCOT_BENCH_BUILD (build dir, default build-bench),
#              BCOT_BENCH_LIGHTS / BCOT_BENCH_MATERIALS (space-separated subsets of the names
#              below), BCOT_BENCH_SETTINGS (space-separated LABEL:key=value,... solver settings;
#              default "region:edge.enabled=false edge:edge.enabled=true").
set -euo pipefail
cd "$(dirname "$0")/.."
frames=${1:-20}
config=${2:-configs/annotate.yaml}
work=${BCOT_BENCH_WORK:-out/bench_bias}
source scripts/bench_lib.sh
bench_build bias_bench
dir=$BENCH_DIR
bench="$dir/tests/bench/bias_bench"
mkdir -p "$work"

declare -A light=(
  [above]="light.azimuth_deg=-45 light.elevation_deg=60"
  [below]="light.azimuth_deg=-45 light.elevation_deg=-50"
  [side]="light.azimuth_deg=180 light.elevation_deg=10"
  [moving]="light.azimuth_deg=-170 light.elevation_deg=45 light.moves=true light.deg_per_frame=9"
)
declare -A material=(
  [matte]="object.specular=0"
  [glossy]="object.specular=1.2 object.shininess=150"
  [dark]="object.color_rgb=[70,62,55] object.specular=0.3"
)
lights=${BCOT_BENCH_LIGHTS:-above below side moving}
materials=${BCOT_BENCH_MATERIALS:-matte glossy dark}
settings=${BCOT_BENCH_SETTINGS:-region:edge.enabled=false edge:edge.enabled=true}

for setting in $settings; do
  name=${setting%%:*}
  sets=()
  IFS=, read -ra pairs <<<"${setting#*:}"
  for pair in "${pairs[@]}"; do sets+=(--set "$pair"); done
  echo "== $name ($config ${setting#*:}), $frames frames"
  header=--header
  for l in $lights; do
    for m in $materials; do
      synth=()
      for pair in ${light[$l]} ${material[$m]}; do synth+=(--synth-set "$pair"); done
      "$bench" --config "$config" --work "$work" --frames "$frames" --label "$l $m" \
        "${synth[@]}" "${sets[@]}" $header
      header=
    done
  done
  echo
done

echo "== Evidence at the true pose (region vs edge measurement), $config"
for l in $lights; do
  synth=()
  for pair in ${light[$l]} ${material[matte]}; do synth+=(--synth-set "$pair"); done
  "$bench" --config "$config" --work "$work" --frames "$frames" --label "$l matte" \
    "${synth[@]}" --set edge.enabled=false --evidence | grep -v '^| [a-z]* [a-z]* | cam[0-9] | [0-9.]* |'
done
