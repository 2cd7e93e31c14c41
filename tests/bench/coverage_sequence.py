#!/usr/bin/python3
"""A copy of a physically based sequence whose images are made from its coverage masks.

Usage: /usr/bin/python3 tests/bench/coverage_sequence.py SRC DST [--sensor] [--jpeg Q]

SRC is a sequence of scripts/pbr_synth.sh (it has gt/mask/<camera>/NNNNNN.png, the renderer's
anti-aliased coverage of the annotated object). DST gets SRC's contract files and ground truth
and, per camera and frame, the image c·F + (1 − c)·B in linear light, sRGB-encoded: c the
coverage, F and B the mean linear colours of SRC's own image inside the object (c = 1) and
in a ring 3–10 px outside it. So each frame keeps the real render's geometry, motion and
mean contrast, and loses everything else the light and the material put into it: shading,
highlights, the rims' reflections, shadows, clutter. Annotated like SRC (`bcot annotate DST
...` + `pbr_errors DST ANN`), the errors are those of the solver, the geometry and the
temporal window alone (docs/notes/issue12_coverage_probe.md).

--sensor adds the render path's sensor model with its defaults (scripts/pbr/pbr_common.py):
lens blur σ 0.6 px and Gaussian + shot noise (σ² = 0.004² + 0.002·v), seeded per frame.
--jpeg Q writes 4:2:0 JPEG frames of quality Q instead of PNG.
"""
import argparse
import os
import sys

import cv2
import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..",
                                "scripts", "pbr"))
import pbr_common as pc  # noqa: E402


def mean_colours(image_bgr8, coverage):
    """Mean linear BGR of the fully covered pixels and of a ring 3-10 px outside them."""
    linear = pc.srgb_to_linear(image_bgr8)
    inside = coverage >= 1.0
    outside = coverage <= 0.0
    if not inside.any():
        return None
    dist = cv2.distanceTransform(outside.astype(np.uint8), cv2.DIST_L2, 5)
    ring = outside & (dist >= 3) & (dist <= 10)
    if not ring.any():
        return None
    return linear[inside].mean(axis=0), linear[ring].mean(axis=0)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("src")
    parser.add_argument("dst")
    parser.add_argument("--sensor", action="store_true")
    parser.add_argument("--jpeg", type=int, default=0)
    args = parser.parse_args()
    cameras = pc.copy_sequence_without_frames(args.src, args.dst)
    sensor = pc.DEFAULTS["sensor"]
    for ci, camera in enumerate(cameras):
        images = sorted(os.listdir(os.path.join(args.src, camera)))
        colours = None
        for frame, name in enumerate(images):
            mask_path = os.path.join(args.src, "gt", "mask", camera, f"{frame:06d}.png")
            coverage = cv2.imread(mask_path, cv2.IMREAD_UNCHANGED)
            if coverage is None:
                raise SystemExit(f"{mask_path}: cannot read")
            coverage = coverage.astype(np.float64) / 65535.0
            image = cv2.imread(os.path.join(args.src, camera, name), cv2.IMREAD_COLOR)
            colours = mean_colours(image, coverage) or colours
            if colours is None:
                raise SystemExit(f"{camera} frame {frame}: the object is not in view")
            fg, bg = colours
            linear = coverage[..., None] * fg + (1.0 - coverage[..., None]) * bg
            if args.sensor:
                linear = pc.apply_sensor(linear, sensor, np.random.default_rng(1000 * ci + frame))
            stem = os.path.splitext(name)[0]
            out = np.round(pc.srgb_encode(linear) * 255.0).astype(np.uint8)
            if args.jpeg > 0:
                cv2.imwrite(os.path.join(args.dst, camera, stem + ".jpg"), out,
                            [cv2.IMWRITE_JPEG_QUALITY, args.jpeg])
            else:
                cv2.imwrite(os.path.join(args.dst, camera, stem + ".png"), out)


if __name__ == "__main__":
    main()
