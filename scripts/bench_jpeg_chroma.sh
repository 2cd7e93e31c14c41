#!/usr/bin/env bash
# The edge stage's correction for JPEG's subsampled chroma on physically based renders (issue 12,
# docs/notes/issue12_jpeg_chroma.md).
#   scripts/bench_jpeg_chroma.sh [SPEC.json ...]
# Default: the small glossy, small diffuse and bright bunny of configs/pbr/. Per scene:
# - renders it once as PNG, keeping Blender's raw output (out/pbr/chroma/<name>-png; reused);
# - from the same raw, its JPEG frames (quality and 4:2:0 of the spec: the frames
#   scripts/bench_pbr.sh annotates) and a PNG copy with only 4:2:0's chroma averaging
#   (tests/bench/jpeg_variants.py subsample, no quantisation);
# - annotates each with configs/annotate.yaml:
#     png                 the lossless frames
#     jpeg as 4:4:4       the JPEG frames measured as full-resolution colour
#     jpeg                the JPEG frames, the chroma shift taken off (edge.chroma_sampling auto)
#     4:2:0 only as 4:4:4 / 4:2:0 only   the subsample-only copy measured both ways
# and prints per scene and setting: mean rotation error (deg), mean |t| and mean signed error
# (bias) per camera axis (mm), both averaged over the two cameras, worst ‖t‖ (mm), CPU ms/frame.
# Needs scripts/setup.sh --with-blender.
set -euo pipefail
cd "$(dirname "$0")/.."
specs=("$@")
if [ ${#specs[@]} -eq 0 ]; then
  specs=(configs/pbr/bunny_small_glossy_fast.json configs/pbr/bunny_small_diffuse_fast.json
         configs/pbr/bunny_bright_soft.json)
fi
py=/usr/bin/python3
nice cmake --build build -j1 --target bcot pbr_errors >/dev/null
root=out/pbr/chroma
mkdir -p "$root"
results=$root/results.tsv
: >"$results"
for spec in "${specs[@]}"; do
  name=$(basename "$spec" .json)
  png=$root/$name-png jpeg=$root/$name-jpeg sub=$root/$name-420only
  if [ ! -d "$png" ]; then
    echo "bench_jpeg_chroma: rendering $png" >&2
    BCOT_PBR_KEEP_RAW=1 scripts/pbr_synth.sh "$spec" "$png" --set sensor.jpeg_quality=0 >&2
  fi
  if [ ! -d "$jpeg" ]; then
    rm -rf "$jpeg.partial" && mkdir -p "$jpeg.partial"
    nice $py scripts/pbr/postprocess.py --spec "$spec" --raw "$png/raw" --out "$jpeg.partial"
    mv "$jpeg.partial" "$jpeg"
  fi
  [ -d "$sub" ] || nice $py tests/bench/jpeg_variants.py "$png" "$sub" subsample
  frames=$(ls "$png/cam0" | wc -l)
  for setting in png jpeg_as_444 jpeg 420only_as_444 420only; do
    case $setting in
      png) seq=$png args=() ;;
      jpeg_as_444) seq=$jpeg args=(--set edge.chroma_sampling=4:4:4) ;;
      jpeg) seq=$jpeg args=() ;;
      420only_as_444) seq=$sub args=() ;;
      420only) seq=$sub args=(--set edge.chroma_sampling=4:2:0) ;;
    esac
    ann=$root/ann/$name/$setting
    rm -rf "$ann" && mkdir -p "$(dirname "$ann")"
    echo "bench_jpeg_chroma: $name $setting" >&2
    TIMEFORMAT='%U %S'
    { time nice build/bcot annotate "$seq" --out "$ann" --config configs/annotate.yaml \
        "${args[@]}" >"$ann.log" 2>&1; } 2>"$ann.time" ||
      [ $? -eq 3 ] ||  # 3: written but rejected by the quality check; still measured
      { echo "bench_jpeg_chroma: bcot annotate failed, see $ann.log" >&2; exit 1; }
    cpu_ms=$(awk -v n="$frames" '{printf "%.0f", ($1 + $2) * 1000 / n}' "$ann.time")
    build/tests/bench/pbr_errors "$seq" "$ann" |
      awk -v s="$name" -v v="$setting" -v c="$cpu_ms" 'BEGIN{OFS="\t"} {print s, v, c, $0}' >>"$results"
  done
done
$py - "$results" <<'PY'
import collections
import sys

# pbr_errors columns after sequence, setting, CPU: cam, frames, rot, rot_max, |x|, |y|, |z|,
# bias x, y, z, sd x, y, z, worst, lost.
rows = collections.defaultdict(list)
order = []
for line in open(sys.argv[1]):
    p = line.rstrip("\n").split("\t")
    key = (p[0], p[1])
    if key not in rows:
        order.append(key)
    rows[key].append((float(p[2]), [float(v) for v in p[4:]]))
print("| scene | frames | rotation ° | \\|x\\| / \\|y\\| / \\|z\\| mm | bias x / y / z mm "
      "| worst mm | CPU ms/frame |")
print("|---|---|---:|---|---|---:|---:|")
for scene, setting in order:
    cams = rows[(scene, setting)]
    mean = lambda i: sum(c[1][i] for c in cams) / len(cams)
    print(f"| {scene} | {setting} | {mean(1):.3f} | {mean(3):.3f} / {mean(4):.3f} / "
          f"{mean(5):.3f} | {mean(6):+.3f} / {mean(7):+.3f} / {mean(8):+.3f} | "
          f"{max(c[1][12] for c in cams):.2f} | {cams[0][0]:.0f} |")
PY
