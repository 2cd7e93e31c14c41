#!/usr/bin/python3
"""A copy of a sequence with every STEP-th frame: the same scene at 1/STEP of its frame rate.

Usage: /usr/bin/python3 tests/bench/subsample_sequence.py SRC DST STEP

SRC is a sequence of the input contract with ground truth (`bcot synth` or scripts/pbr_synth.sh).
DST gets frames 0, STEP, 2·STEP, ... of SRC renumbered from 0: every camera's images, the
timestamps, gt/rig_from_object.txt, gt/world_from_*.txt, gt/<camera>/pose.txt and
gt/mask/<camera>/ when present; rig.yaml, object.yaml, the model and init_pose.txt (frame 0 is
kept) are copied, and pbr_timing.json when present. The object then moves STEP times as far
between frames, and its motion changes STEP² times as much, which is what a constant-velocity
prediction misses (docs/notes/issue12_fast_motion.md). Annotate DST like SRC and compare with
`pbr_errors DST ANN`. DST is replaced if it exists.
"""
import os
import shutil
import sys

POSE_FILES = ("rig_from_object.txt", "world_from_object.txt", "world_from_rig.txt")


def fail(message):
    sys.exit(f"subsample_sequence: {message}")


def rows_of(path, frames):
    rows = [r for r in open(path).read().splitlines() if r.strip()]
    if len(rows) != frames:
        fail(f"{path}: {len(rows)} rows, expected one per frame ({frames})")
    return rows


def main():
    if len(sys.argv) != 4:
        fail("usage: subsample_sequence.py SRC DST STEP")
    src, dst = sys.argv[1], sys.argv[2]
    try:
        step = int(sys.argv[3])
    except ValueError:
        fail(f"STEP: '{sys.argv[3]}' is not an integer")
    if step < 1:
        fail(f"STEP: {step}, must be >= 1")
    stamps_path = os.path.join(src, "timestamps.csv")
    if not os.path.isfile(stamps_path):
        fail(f"{stamps_path}: not found (SRC must be a sequence directory)")
    stamps = [r for r in open(stamps_path).read().splitlines() if r.strip()]
    header, stamp_rows = stamps[0], stamps[1:]
    cameras = header.split(",")[1:]
    frames = len(stamp_rows)
    keep = list(range(0, frames, step))
    if len(keep) < 2:
        fail(f"{frames} frames at step {step} leave {len(keep)}: nothing to track")

    if os.path.exists(dst):
        shutil.rmtree(dst)
    os.makedirs(os.path.join(dst, "gt"))
    for name in ("rig.yaml", "object.yaml", "init_pose.txt"):
        shutil.copy(os.path.join(src, name), dst)
    # The render's own record, which scripts/bench_pbr.sh prints with the scene's checks.
    if os.path.isfile(os.path.join(src, "pbr_timing.json")):
        shutil.copy(os.path.join(src, "pbr_timing.json"), dst)
    shutil.copytree(os.path.join(src, "model"), os.path.join(dst, "model"))
    with open(os.path.join(dst, "timestamps.csv"), "w") as out:
        out.write(header + "\n")
        for i, k in enumerate(keep):
            out.write(",".join([str(i)] + stamp_rows[k].split(",")[1:]) + "\n")

    def copy_images(sub):
        folder = os.path.join(src, sub)
        by_frame = {os.path.splitext(f)[0]: f for f in os.listdir(folder)}
        os.makedirs(os.path.join(dst, sub))
        for i, k in enumerate(keep):
            name = by_frame.get(f"{k:06d}")
            if name is None:
                fail(f"{folder}: no image of frame {k}")
            ext = os.path.splitext(name)[1]
            shutil.copy(os.path.join(folder, name), os.path.join(dst, sub, f"{i:06d}{ext}"))

    def copy_rows(sub):
        rows = rows_of(os.path.join(src, sub), frames)
        with open(os.path.join(dst, sub), "w") as out:
            out.write("\n".join(rows[k] for k in keep) + "\n")

    for camera in cameras:
        copy_images(camera)
        if os.path.isfile(os.path.join(src, "gt", camera, "pose.txt")):
            os.makedirs(os.path.join(dst, "gt", camera))
            copy_rows(os.path.join("gt", camera, "pose.txt"))
        if os.path.isdir(os.path.join(src, "gt", "mask", camera)):
            copy_images(os.path.join("gt", "mask", camera))
    for name in POSE_FILES:
        if os.path.isfile(os.path.join(src, "gt", name)):
            copy_rows(os.path.join("gt", name))
    print(f"{dst}: frames {', '.join(str(k) for k in keep[:4])}, ... of {src} ({len(keep)} frames)")


if __name__ == "__main__":
    main()
