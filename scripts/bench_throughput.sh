#!/usr/bin/env bash
# Whole-process annotation throughput (issue 19): `bcot batch` over a directory of binocular
# 960×768 JPEG sequences, as a lab runs it on a corpus. Everything a frame costs is counted:
# process start, reading the rig and mesh, JPEG decode, the per-frame solves, the temporal
# window, the quality check and the report files.
#
# Sequences: configs/synth/shaded_rim.yaml (two cameras 90° apart, 960×768, JPEG 4:2:0, shaded
# rims and same-coloured clutter) with the bunny, the pinion and the spool, seeds 21, 22, 23,
# synthesized once into out/bench_throughput/seq/ (reused while the frame count is the same).
#
# Usage: scripts/bench_throughput.sh [frames per sequence, default 60] [jobs, default 2]
#                                    [annotate config, default configs/annotate.yaml]
# Environment: BCOT_BENCH_BUILD (build dir, default build-bench), BCOT_BENCH_WORK (default
# out/bench_throughput). Prints a markdown table: frame pairs, wall time, frame pairs per second
# (wall), CPU ms per frame pair (user + sys of every process) and the largest resident set of
# one annotate process.
set -euo pipefail
cd "$(dirname "$0")/.."
frames=${1:-60}
jobs=${2:-2}
config=${3:-configs/annotate.yaml}
work=${BCOT_BENCH_WORK:-out/bench_throughput}
source scripts/bench_lib.sh
bench_build bcot
dir=$BENCH_DIR
bcot="$dir/bcot"

seq_root="$work/seq_${frames}f"
objects=(bunny:21:data/meshes/bunny.obj pinion:22:data/meshes/pinion.off
         spool:23:data/meshes/spool.off)
mkdir -p "$seq_root"
for entry in "${objects[@]}"; do
  IFS=: read -r name seed mesh <<<"$entry"
  [ -f "$seq_root/$name/rig.yaml" ] && continue
  echo "bench_throughput: synthesizing $seq_root/$name" >&2
  rm -rf "$seq_root/$name.partial"
  "$bcot" synth --config configs/synth/shaded_rim.yaml --out "$seq_root/$name.partial" \
    --set "seed=$seed" --set "object.mesh=$PWD/$mesh" --set "motion.num_frames=$frames" >/dev/null
  mv "$seq_root/$name.partial" "$seq_root/$name"
done

out="$work/ann"
rm -rf "$out"
timing="$work/time.txt"
# GNU time: wall seconds, user + sys seconds of the batch and every child it waited for, and the
# largest resident set (KiB) among them.
status=0
/usr/bin/time -f '%e %U %S %M' -o "$timing" \
  "$bcot" batch "$seq_root" --out "$out" --jobs "$jobs" --config "$config" --quiet || status=$?
# 3: every sequence written, some rejected by the quality check; still a complete run.
if [ "$status" -ne 0 ] && [ "$status" -ne 3 ]; then
  echo "bench_throughput: bcot batch failed (exit $status)" >&2
  exit 1
fi
pairs=$((frames * ${#objects[@]}))
# GNU time writes "Command exited with non-zero status N" first when the exit status is not 0.
read -r wall user sys rss_kib < <(tail -n 1 "$timing")
echo
echo "| sequences | frame pairs | jobs | config | wall s | frame pairs/s | CPU ms/frame pair | peak RSS MiB |"
echo "|---:|---:|---:|---|---:|---:|---:|---:|"
awk -v n="${#objects[@]}" -v p="$pairs" -v j="$jobs" -v c="$config" -v w="$wall" -v u="$user" \
  -v s="$sys" -v r="$rss_kib" 'BEGIN {
    printf "| %d | %d | %d | %s | %.1f | %.2f | %.0f | %.0f |\n", n, p, j, c, w, p / w,
           (u + s) * 1000 / p, r / 1024 }'
