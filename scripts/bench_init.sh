#!/usr/bin/env bash
# Capture range of frame 0 (MultiViewTracker::Initialize): `bcot annotate` from an
# init_pose.txt perturbed by R° / T mm about the object's bounding-box centre (bcot synth's
# init.rotation_deg / init.translation_mm, a seeded random axis and direction), on short
# demo-scene sequences (configs/synth/demo.yaml, binocular 90°), with the bootstrap passes
# until convergence (default) and with at most two passes (the former fixed two). Prints the
# frame-0 error (rotation, and translation at the bounding-box centre) per start and seed.
#
# Usage: scripts/bench_init.sh [seeds, default 3]
# Environment: BCOT_BENCH_WORK (default out/bench_init).
set -euo pipefail
cd "$(dirname "$0")/.."
seeds=${1:-3}
work=${BCOT_BENCH_WORK:-out/bench_init}
dir=build-bench
cmake -S . -B "$dir" -G Ninja -DCMAKE_BUILD_TYPE=Release -DBCOT_BUILD_TESTS=OFF \
  -DBCOT_BUILD_BENCHMARKS=ON >/dev/null
cmake --build "$dir" --target bcot >/dev/null
mkdir -p "$work"
# Frame-0 rotation error (deg) and translation error at the bbox centre (mm) of an annotation
# against the sequence's ground truth (OBJ meshes).
frame0_error() {
  python3 - "$1" "$2" <<'PY'
import math, re, sys
annotation, seq = sys.argv[1], sys.argv[2]
def first_pose(path):
    for line in open(path):
        v = [float(x) for x in line.split()]
        if len(v) >= 12:
            return v[:9], v[9:12]
text = open(seq + "/object.yaml").read()
mesh = re.search(r"mesh: (\S+)", text).group(1)
scale = float(re.search(r"unit_to_mm: (\S+)", text).group(1))
vertices = [list(map(float, l.split()[1:4])) for l in open(seq + "/" + mesh) if l.startswith("v ")]
centre = [scale * (min(v[i] for v in vertices) + max(v[i] for v in vertices)) / 2 for i in range(3)]
(ra, ta), (rb, tb) = first_pose(annotation), first_pose(seq + "/gt/rig_from_object.txt")
trace = sum(ra[3 * r + k] * rb[3 * r + k] for r in range(3) for k in range(3))
angle = math.degrees(math.acos(max(-1.0, min(1.0, (trace - 1) / 2))))
at = lambda rot, t: [t[r] + sum(rot[3 * r + k] * centre[k] for k in range(3)) for r in range(3)]
print(f"{angle:.3f}° / {math.dist(at(ra, ta), at(rb, tb)):.2f} mm")
PY
}
echo "| start | seed | frame 0, passes until converged | frame 0, at most two passes |"
echo "|---|---:|---|---|"
for start in "5 10" "10 20" "15 30" "20 40" "30 50"; do
  read -r deg mm <<<"$start"
  for seed in $(seq 1 "$seeds"); do
    seq_dir="$work/init_${deg}_${mm}_$seed"
    if [ ! -f "$seq_dir/rig.yaml" ]; then
      "$dir/bcot" synth --quiet --config configs/synth/demo.yaml --out "$seq_dir" \
        --set seed="$seed" --set motion.num_frames=2 --set init.rotation_deg="$deg" \
        --set init.translation_mm="$mm" >/dev/null 2>"$seq_dir.synth.log"
    fi
    row="| ${deg}° / ${mm} mm | $seed"
    for passes in 8 2; do
      out="$seq_dir.passes$passes"
      "$dir/bcot" annotate --quiet "$seq_dir" --out "$out" --config configs/annotate.yaml \
        --set window.enabled=false --set tracker.bootstrap_passes=$passes >/dev/null \
        2>"$out.log"
      row="$row | $(frame0_error "$out/rig_from_object.txt" "$seq_dir")"
    done
    echo "$row |"
  done
done
