#!/usr/bin/env bash
# Capture rate of `bcot capture` with Aravis' fake cameras (no hardware): frame sets per second
# for one in-process fake camera (Fake_1) and for two cameras (Fake_1 + the GigE Vision fake
# camera on loopback), software-triggered, at several camera frame rates and PNG levels.
#   scripts/bench_capture.sh [BUILD_DIR] [FRAME_SETS]
set -euo pipefail

build_dir=${1:-build}
frame_sets=${2:-200}
bcot="$build_dir/bcot"
[[ -x "$bcot" ]] || { echo "bench_capture: $bcot not found (build first)" >&2; exit 1; }
command -v arv-fake-gv-camera-0.8 >/dev/null || { echo "bench_capture: arv-fake-gv-camera-0.8 missing (apt-get install aravis-tools)" >&2; exit 1; }

work=$(mktemp -d)
gv_pid=""
cleanup() {
  [[ -n "$gv_pid" ]] && kill "$gv_pid" 2>/dev/null && wait "$gv_pid" 2>/dev/null || true
  rm -rf "$work"
}
trap cleanup EXIT

arv-fake-gv-camera-0.8 -i 127.0.0.1 -s GV01 >/dev/null 2>&1 &
gv_pid=$!
sleep 1.5

# run NAME MODE FPS PNG_LEVEL CAMERA_IDS...   (FPS "-" = keep the camera's frame rate)
run() {
  local name=$1 mode=$2 fps=$3 png=$4
  shift 4
  local config="$work/config.yaml" out="$work/seq" index=0
  {
    echo "aravis: {enable_fake_interface: true}"
    echo "trigger: {mode: $mode}"
    echo "cameras:"
    for id in "$@"; do
      echo -n "  - {name: cam$index, device_id: $id, pixel_format: Mono8"
      [[ "$fps" != "-" ]] && echo -n ", frame_rate_hz: $fps"
      echo "}"
      index=$((index + 1))
    done
    echo "recording: {max_frame_sets: $frame_sets, max_skew_ms: $skew_ms, png_compression: $png}"
  } > "$config"
  local log
  log=$("$bcot" capture --config "$config" --out "$out" 2>&1) || { echo "$log" >&2; return 1; }
  # Last status line: "... | missed M | unmatched U"; summary: "... wrote N frame sets to DIR in S s"
  local sets seconds missed unmatched
  sets=$(sed -n 's/.*wrote \([0-9]*\) frame sets.* in \([0-9.]*\) s$/\1/p' <<<"$log")
  seconds=$(sed -n 's/.*wrote \([0-9]*\) frame sets.* in \([0-9.]*\) s$/\2/p' <<<"$log")
  missed=$(grep -o 'missed [0-9]*' <<<"$log" | tail -1 | cut -d' ' -f2)
  unmatched=$(grep -o 'unmatched [0-9]*' <<<"$log" | tail -1 | cut -d' ' -f2)
  printf "| %-20s | %-8s | %7s | %3s | %10s | %6s | %7s | %6s | %9s |\n" "$name" "$mode" "$fps" "$png" \
    "$sets" "$seconds" "$(awk -v n="$sets" -v s="$seconds" 'BEGIN { printf "%.1f", n / s }')" \
    "$missed" "$unmatched"
  rm -rf "$out"
}

echo "bcot capture, 512x512 Mono8 fake cameras, $frame_sets frame sets per row"
printf "| %-20s | %-8s | %7s | %3s | %10s | %6s | %7s | %6s | %9s |\n" cameras trigger "fps set" png \
  "frame sets" "time s" "sets/s" missed unmatched
echo "|----------------------|----------|---------|-----|------------|--------|---------|--------|-----------|"
skew_ms=10
run "Fake_1" software - 1 Fake_1
run "Fake_1 + GV01" software - 1 Fake_1 Aravis-Fake-GV01
run "Fake_1 + GV01" software - 0 Fake_1 Aravis-Fake-GV01
run "Fake_1 + GV01" software - 6 Fake_1 Aravis-Fake-GV01
skew_ms=2
run "Fake_1" free_run 200 1 Fake_1
run "Fake_1 + GV01" free_run 100 1 Fake_1 Aravis-Fake-GV01
