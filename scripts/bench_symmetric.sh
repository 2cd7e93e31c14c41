#!/usr/bin/env bash
# Bodies of revolution (docs/method.md, "Symmetric objects"): each sequence annotated with the
# symmetry found and held (symmetry.detect: true, the default) and without (false, every pose
# free to turn about the axis), then measured by tests/bench/pbr_errors against ground truth:
# the rotation error leaves out the turn about the axis (the axis's own error), translation at
# the bounding-box centre, and how far the annotation turns about the axis from one frame to the
# next beside the ground truth's own turn. Sequences (bcot synth, configs/synth/shaded_rim.yaml):
#   round_spool_23, round_spool_24  a 256-sided spool (flanges 120 mm across, a 40 mm core),
#                                   written here, seeds 23 and 24
#   spool_32                        data/meshes/spool.off (32 sides: its facets show in the
#                                   renders of that mesh), seed 23 as in bench_throughput.sh
# and, when it was rendered (scripts/bench_pbr.sh), the Cycles spool out/pbr/spool_dark.
#
# Usage: scripts/bench_symmetric.sh [frames per synthetic sequence, default 40]
# Environment: BCOT_BENCH_WORK (default out/bench_symmetric), BCOT_BENCH_BUILD (an existing
# Release build directory configured with -DBCOT_BUILD_BENCHMARKS=ON, used as it is; default:
# build-bench, configured here).
set -euo pipefail
cd "$(dirname "$0")/.."
frames=${1:-40}
work=${BCOT_BENCH_WORK:-out/bench_symmetric}
source scripts/bench_lib.sh
bench_build bcot pbr_errors
dir=$BENCH_DIR
mkdir -p "$work"

# The round spool: the profile (x, r) in mm revolved in 256 steps, outward-facing triangles.
round_mesh="$work/round_spool.off"
if [ ! -f "$round_mesh" ]; then
  python3 - "$round_mesh" <<'PY'
import math
import sys

profile = [(-48, 0), (-48, 60), (-40, 60), (-40, 20), (40, 20), (40, 60), (48, 60), (48, 0)]
steps = 256
vertices, index = [], {}

def vertex(i, k):
    x, r = profile[i]
    key = (i, 0 if r == 0 else k % steps)
    if key not in index:
        a = 2.0 * math.pi * (k % steps) / steps
        index[key] = len(vertices)
        vertices.append((x, r * math.cos(a), r * math.sin(a)))
    return index[key]

triangles = []
for i in range(len(profile) - 1):
    for k in range(steps):
        a, b, c, d = vertex(i, k), vertex(i, k + 1), vertex(i + 1, k), vertex(i + 1, k + 1)
        for t in ((a, d, c), (a, b, d)):  # outward for this profile's direction
            if len(set(t)) == 3:
                triangles.append(t)
with open(sys.argv[1], "w") as f:
    f.write(f"OFF\n{len(vertices)} {len(triangles)} 0\n")
    f.writelines(f"{x:.6f} {y:.6f} {z:.6f}\n" for x, y, z in vertices)
    f.writelines(f"3 {a} {b} {c}\n" for a, b, c in triangles)
PY
fi

names=() seqs=()
for entry in round_spool_23:23:"$round_mesh" round_spool_24:24:"$round_mesh" \
             spool_32:23:data/meshes/spool.off; do
  IFS=: read -r name seed mesh <<<"$entry"
  seq="$work/$name"
  if [ ! -f "$seq/rig.yaml" ]; then
    rm -rf "$seq.partial"
    "$dir/bcot" synth --quiet --config configs/synth/shaded_rim.yaml --out "$seq.partial" \
      --set "seed=$seed" --set "object.mesh=$PWD/$mesh" --set "motion.num_frames=$frames" 2>/dev/null
    mv "$seq.partial" "$seq"
  fi
  names+=("$name") seqs+=("$seq")
done
if [ -d out/pbr/spool_dark ]; then names+=(cycles_spool_dark) seqs+=(out/pbr/spool_dark); fi

echo "| sequence | symmetry.detect | rotation ° (axis) | \|x\| / \|y\| / \|z\| mm (mean of cameras) | worst ‖t‖ mm | turn about the axis per frame: annotation / truth, mean (max) ° |"
echo "|---|---|---:|---|---:|---|"
for i in "${!names[@]}"; do
  name=${names[$i]} seq=${seqs[$i]}
  for detect in true false; do
    ann="$work/$name.$detect"
    rm -rf "$ann"
    # Exit 3 (written, rejected by the quality check) is an outcome this bench measures.
    "$dir/bcot" annotate --quiet "$seq" --out "$ann" --config configs/annotate.yaml \
      --set "symmetry.detect=$detect" 2>"$ann.log" || [ $? -eq 3 ]
    "$dir/tests/bench/pbr_errors" "$seq" "$ann" >"$ann.rows" 2>"$ann.note"
    python3 - "$name" "$detect" "$ann.rows" "$ann.note" <<'PY'
import re
import sys

name, detect, rows_path, note_path = sys.argv[1:5]
rows = [line.split("\t") for line in open(rows_path) if "\t" in line and "#" not in line.split("\t")[0]]
rotation = float(rows[0][2])
axes = [sum(float(r[4 + k]) for r in rows) / len(rows) for k in range(3)]
worst = max(float(r[13]) for r in rows)
turns = re.findall(r"([0-9.]+)° mean, ([0-9.]+)° max", open(note_path).read())
turn = (f"{float(turns[0][0]):.3f} ({float(turns[0][1]):.3f}) / "
        f"{float(turns[1][0]):.3f} ({float(turns[1][1]):.3f})") if len(turns) == 2 else "–"
print(f"| {name} | {detect} | {rotation:.4f} | {axes[0]:.4f} / {axes[1]:.4f} / {axes[2]:.4f} "
      f"| {worst:.3f} | {turn} |")
PY
  done
done
