#!/usr/bin/env bash
# `bcot init` without init_pose.txt: success rate and time per init on bcot synth sequences.
# Frame 0 of configs/synth/demo.yaml (binocular 90°, 640×512, cluttered and plain backdrops,
# distractors), 20 frames, the object moving 8 mm and 2° per frame (it crosses more than its own
# size over the sequence, as a handheld object does over a few hundred frames), with each mesh of
# BCOT_BENCH_MESHES and each variant of BCOT_BENCH_VARIANTS (default all three):
#   plain   the demo scene (object 150 mm, ~200 px);
#   glossy  sharp highlights (specular 1.2, shininess 150) and half of the clutter and of the
#           distractors in colours close to the object's;
#   small   the object 40 mm long (~60 px).
# Three ways of starting: clicks on the object centre (the true projection of the mesh's
# bounding-box centre moved by a seeded uniform offset of up to ±JITTER px per axis):
#   2 clicks: cam0 and cam1 (the centre is triangulated);
#   1 click:  cam0 only (the depth along the ray is searched with the orientation);
#   0 clicks: none (the object found by its motion over the sequence).
# A run succeeds when the written pose is within 5° and 10 mm (object centre) of gt/. Several
# meshes are (nearly) rotationally symmetric, so their rotation about the axis is not
# defined by the images: the table also counts ADD-S < 0.1 d (mean distance of the model points
# to the nearest model point of the truth, d the longest bounding-box side; the BOP criterion
# for symmetric objects). Prints one row per sequence and mode, then the tables: per mode, per
# variant and per mesh, success rates and mean time per init.
#
# Usage: scripts/bench_bcot_init.sh [seeds per mesh and variant, default 1] [jitter px, default 10]
# Environment: BCOT_BENCH_WORK (default out/bench_bcot_init), BCOT_BUILD (default build),
# BCOT_BENCH_MESHES (space-separated mesh files, default the three of data/meshes),
# BCOT_BENCH_VARIANTS (default "plain glossy small"), BCOT_BENCH_MODES (default "2 1 0").
set -euo pipefail
cd "$(dirname "$0")/.."
seeds=${1:-1}
jitter=${2:-10}
work=${BCOT_BENCH_WORK:-out/bench_bcot_init}
build=${BCOT_BUILD:-build}
bcot="$build/bcot"
if [ ! -x "$bcot" ]; then
  cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
  cmake --build "$build" --target bcot >/dev/null
fi
mkdir -p "$work"
rows="$work/rows.txt"
: >"$rows"
read -ra meshes <<<"${BCOT_BENCH_MESHES:-data/meshes/bunny.obj data/meshes/spool.off data/meshes/pinion.off}"
read -ra variants <<<"${BCOT_BENCH_VARIANTS:-plain glossy small}"
read -ra modes <<<"${BCOT_BENCH_MODES:-2 1 0}"
variant_settings() {
  case "$1" in
    plain) ;;
    glossy) echo "--set object.specular=1.2 --set object.shininess=150" \
      "--set background.similar_color_fraction=0.5 --set distractors.similar_color_fraction=0.5" ;;
    small) echo "--set object.size_mm=40" ;;
    *) echo "bench_bcot_init: unknown variant $1" >&2; exit 2 ;;
  esac
}
for mesh in "${meshes[@]}"; do
  mesh=$(realpath "$mesh")
  object=$(basename "$mesh")
  object=${object%%.*}
  for variant in "${variants[@]}"; do
    for seed in $(seq 1 "$seeds"); do
      name="${object}_${variant}_$seed"
      seq_dir="$work/$name"
      if [ ! -f "$seq_dir/rig.yaml" ]; then
        read -ra settings <<<"$(variant_settings "$variant")"
        "$bcot" synth --quiet --config configs/synth/demo.yaml --out "$seq_dir" \
          --set seed="$seed" --set motion.num_frames=20 --set motion.translation_mm_per_frame=8 \
          --set object.mesh="$mesh" "${settings[@]}" >/dev/null 2>"$seq_dir.synth.log"
        rm -f "$seq_dir/init_pose.txt"
      fi
      for mode in "${modes[@]}"; do
        case $mode in
          2) read -ra clicks <<<"$(python3 scripts/init_bench_util.py clicks "$seq_dir" 0 cam0,cam1 \
               "$jitter" "$seed")" ;;
          1) read -ra clicks <<<"$(python3 scripts/init_bench_util.py clicks "$seq_dir" 0 cam0 \
               "$jitter" "$seed")" ;;
          0) clicks=() ;;
        esac
        out="$work/${name}_${mode}click.txt"
        start=$(date +%s.%N)
        if "$bcot" init "$seq_dir" "${clicks[@]}" --out "$out" --overwrite \
          >"$out.log" 2>&1; then
          seconds=$(echo "$(date +%s.%N) - $start" | bc)
          read -r deg mm adds <<<"$(python3 scripts/init_bench_util.py error "$seq_dir" 0 "$out")"
        else
          seconds=$(echo "$(date +%s.%N) - $start" | bc)
          deg=nan mm=nan adds=nan
        fi
        printf '%s %s %s %s %s %s %s %s\n' "$object" "$seed" "$mode" "$deg" "$mm" "$adds" \
          "$seconds" "$variant" | tee -a "$rows"
      done
    done
  done
done
python3 - "$rows" "$jitter" <<'PY'
import sys
rows = [l.split() for l in open(sys.argv[1]) if l.strip()]
LABELS = {"2": "2 views", "1": "1 view, depth searched", "0": "none (moving object found)"}


def line(label, sel):
    ok = lambda r, f: r[3] != "nan" and f(r)
    strict = sum(ok(r, lambda r: float(r[3]) <= 5 and float(r[4]) <= 10) for r in sel)
    adds = sum(ok(r, lambda r: float(r[5]) < 0.1) for r in sel)
    n = max(1, len(sel))
    mean_s = sum(float(r[6]) for r in sel) / n
    return "| %s | %d | %d (%.0f %%) | %d (%.0f %%) | %.1f |" % (
        label, len(sel), strict, 100.0 * strict / n, adds, 100.0 * adds / n, mean_s)


MODES = [m for m in ("2", "1", "0") if any(r[2] == m for r in rows)]
print()
print("| clicks (±%s px) | inits | within 5° / 10 mm | ADD-S < 0.1 d | mean time per init (s) |"
      % sys.argv[2])
print("|---|---:|---:|---:|---:|")
for mode in MODES:
    print(line(LABELS[mode], [r for r in rows if r[2] == mode]))
for key, index, title in (("variant", 7, "variant"), ("mesh", 0, "mesh")):
    print()
    print("| %s, clicks | inits | within 5° / 10 mm | ADD-S < 0.1 d | mean time per init (s) |" % title)
    print("|---|---:|---:|---:|---:|")
    for value in dict.fromkeys(r[index] for r in rows):
        for mode in MODES:
            print(line("%s, %s" % (value, LABELS[mode]),
                       [r for r in rows if r[index] == value and r[2] == mode]))
PY
