#!/usr/bin/env bash
# Renders one physically based sequence (issue 12) with Blender Cycles, headless on the CPU:
# the input contract `bcot synth` writes (rig.yaml, object.yaml + model/, <camera>/NNNNNN.png
# or .jpg, init_pose.txt, timestamps.csv) plus gt/ (poses like `bcot synth`, and
# gt/mask/<camera>/NNNNNN.png: 16-bit coverage of the annotated object alone).
#   scripts/pbr_synth.sh configs/pbr/bunny_plastic.json out/pbr/bunny [--set render.samples=16 ...]
# Needs `scripts/setup.sh --with-blender`. The sequence is built in OUT.partial/ (an interrupted
# render resumes there) and renamed to OUT only when complete. Threads: BCOT_PBR_THREADS (2).
# BCOT_PBR_KEEP_RAW=1 keeps Blender's raw renders in OUT/raw (to re-run only the sensor model,
# scripts/pbr/postprocess.py, with other sensor.* settings).
set -euo pipefail
if [ $# -lt 2 ]; then sed -n '2,9p' "$0"; exit 2; fi
spec=$1 out=$2
shift 2
sets=()
while [ $# -gt 0 ]; do
  case "$1" in
    --set) sets+=(--set "$2"); shift 2 ;;
    *) echo "pbr_synth: unknown argument $1" >&2; exit 2 ;;
  esac
done
here=$(cd "$(dirname "$0")" && pwd)
command -v blender >/dev/null || { echo "pbr_synth: blender not found (scripts/setup.sh --with-blender)" >&2; exit 1; }
if [ -e "$out" ]; then echo "pbr_synth: $out exists" >&2; exit 2; fi
partial="$out.partial"
mkdir -p "$partial/raw"
# One run per output: a second run on the same folder would rename frames under the first.
exec 9>"$partial/.lock"
flock -n 9 || { echo "pbr_synth: another run is writing $partial" >&2; exit 1; }
nice blender -b --factory-startup --python-exit-code 1 --python "$here/pbr/render_blender.py" -- \
  --spec "$spec" --raw "$partial/raw" "${sets[@]}" >"$partial/blender.log" 2>&1 ||
  { echo "pbr_synth: Blender failed, see $partial/blender.log" >&2; tail -20 "$partial/blender.log" >&2; exit 1; }
/usr/bin/python3 "$here/pbr/postprocess.py" --spec "$spec" --raw "$partial/raw" --out "$partial" "${sets[@]}"
[ "${BCOT_PBR_KEEP_RAW:-0}" = 1 ] || rm -rf "$partial/raw"
rm -f "$partial/.lock"  # the open descriptor keeps the lock until exit
mv "$partial" "$out"
echo "pbr_synth: wrote $out ($(cat "$out/pbr_timing.json"))"
