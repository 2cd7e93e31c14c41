#!/usr/bin/python3
"""A copy of a PNG sequence with one of JPEG's two losses applied to its frames, the other not.

Usage: /usr/bin/python3 tests/bench/jpeg_variants.py SRC DST subsample
       /usr/bin/python3 tests/bench/jpeg_variants.py SRC DST subsample_linear
       /usr/bin/python3 tests/bench/jpeg_variants.py SRC DST quantise [--quality 90]

SRC's frames must be PNG (scripts/pbr_synth.sh SPEC SRC --set sensor.jpeg_quality=0). Each
frame goes to JFIF's full-range YCbCr and back, in between:
- subsample: 4:2:0 chroma as libjpeg makes and decodes it (Cb and Cr averaged over 2x2 pixels,
  then brought back by libjpeg's "fancy" upsampling, weights 9/3/3/1 of the nearest four
  half-resolution samples), no quantisation;
- subsample_linear: the same averaging and upsampling of the same colour matrix applied to
  linear light instead of the sRGB codes (no codec does this; it separates what the averaging's
  geometry costs from what averaging gamma-encoded values adds);
- quantise: every channel at full resolution through an 8x8 DCT quantised with the standard
  luminance and chrominance tables scaled to --quality, as baseline JPEG 4:4:4 does.
The frames stay PNG files, so only the named loss is in them. Annotated like SRC (`bcot
annotate DST ...` + `pbr_errors DST ANN`), they show which of the two costs the precision
(docs/notes/issue12_coverage_floor.md).
"""
import argparse
import os
import sys

import cv2
import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..",
                                "scripts", "pbr"))
import pbr_common as pc  # noqa: E402

LUMINANCE_TABLE = np.array([
    16, 11, 10, 16, 24, 40, 51, 61, 12, 12, 14, 19, 26, 58, 60, 55,
    14, 13, 16, 24, 40, 57, 69, 56, 14, 17, 22, 29, 51, 87, 80, 62,
    18, 22, 37, 56, 68, 109, 103, 77, 24, 35, 55, 64, 81, 104, 113, 92,
    49, 64, 78, 87, 103, 121, 120, 101, 72, 92, 95, 98, 112, 100, 103, 99,
], float).reshape(8, 8)
CHROMINANCE_TABLE = np.array(
    [17, 18, 24, 47, 99, 99, 99, 99, 18, 21, 26, 66, 99, 99, 99, 99,
     24, 26, 56, 99, 99, 99, 99, 99, 47, 66, 99, 99, 99, 99, 99, 99] + [99] * 32,
    float).reshape(8, 8)


def scaled_table(base, quality):
    """libjpeg's jpeg_quality_scaling and table clamping."""
    scale = 5000 / quality if quality < 50 else 200 - 2 * quality
    return np.clip(np.floor((base * scale + 50) / 100), 1, 255)


def to_ycbcr(bgr):
    b, g, r = (bgr[..., i].astype(float) for i in range(3))
    y = 0.299 * r + 0.587 * g + 0.114 * b
    cb = -0.168736 * r - 0.331264 * g + 0.5 * b + 128
    cr = 0.5 * r - 0.418688 * g - 0.081312 * b + 128
    return y, cb, cr


def to_bgr_float(y, cb, cr):
    r = y + 1.402 * (cr - 128)
    g = y - 0.344136 * (cb - 128) - 0.714136 * (cr - 128)
    b = y + 1.772 * (cb - 128)
    return np.stack([b, g, r], -1)


def to_bgr(y, cb, cr):
    return np.clip(np.round(to_bgr_float(y, cb, cr)), 0, 255).astype(np.uint8)


def quantise(channel, table):
    h, w = channel.shape
    padded = np.pad(channel - 128, ((0, -h % 8), (0, -w % 8)), mode="edge")
    out = np.empty_like(padded)
    for i in range(0, padded.shape[0], 8):
        for j in range(0, padded.shape[1], 8):
            coefficients = cv2.dct(padded[i:i + 8, j:j + 8])
            out[i:i + 8, j:j + 8] = cv2.idct(np.round(coefficients / table) * table)
    return out[:h, :w] + 128


def mean2x2(channel):
    """The means of the 2x2 blocks (an odd last row or column left out)."""
    h, w = channel.shape
    return channel[:h - h % 2, :w - w % 2].reshape(h // 2, 2, w // 2, 2).mean((1, 3))


def fancy_upsample(half):
    """libjpeg's h2v2 fancy upsampling: weights 9/3/3/1 of the nearest four samples, edges
    replicated."""
    p = np.pad(half, 1, mode="edge")
    hh, ww = half.shape
    out = np.empty((2 * hh, 2 * ww))
    for dy in (0, 1):
        for dx in (0, 1):
            vy, vx = (-1 if dy == 0 else 1), (-1 if dx == 0 else 1)
            nearest = p[1:-1, 1:-1]
            beside = p[1:-1, 1 + vx:ww + 1 + vx]
            above_below = p[1 + vy:hh + 1 + vy, 1:-1]
            diagonal = p[1 + vy:hh + 1 + vy, 1 + vx:ww + 1 + vx]
            out[dy::2, dx::2] = (9 * nearest + 3 * beside + 3 * above_below + diagonal) / 16
    return out


def subsample(channel):
    """2x2 average, then libjpeg's h2v2 fancy upsampling (an odd last row or column kept)."""
    out = fancy_upsample(mean2x2(channel))
    result = channel.copy()
    result[:out.shape[0], :out.shape[1]] = out
    return result


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("src")
    parser.add_argument("dst")
    parser.add_argument("mode", choices=["subsample", "subsample_linear", "quantise"])
    parser.add_argument("--quality", type=int, default=90)
    args = parser.parse_args()
    cameras = pc.copy_sequence_without_frames(args.src, args.dst)
    for camera in cameras:
        for name in sorted(os.listdir(os.path.join(args.src, camera))):
            if not name.endswith(".png"):
                raise SystemExit(f"{args.src}/{camera}/{name}: not PNG")
            image = cv2.imread(os.path.join(args.src, camera, name))
            if args.mode == "subsample_linear":
                y, cb, cr = to_ycbcr(255.0 * pc.srgb_to_linear(image))
                linear = to_bgr_float(y, subsample(cb), subsample(cr)) / 255.0
                encoded = np.round(255.0 * pc.srgb_encode(linear)).astype(np.uint8)
                cv2.imwrite(os.path.join(args.dst, camera, name), encoded)
                continue
            y, cb, cr = to_ycbcr(image)
            if args.mode == "subsample":
                cb, cr = subsample(cb), subsample(cr)
            else:
                y = quantise(y, scaled_table(LUMINANCE_TABLE, args.quality))
                cb = quantise(cb, scaled_table(CHROMINANCE_TABLE, args.quality))
                cr = quantise(cr, scaled_table(CHROMINANCE_TABLE, args.quality))
            cv2.imwrite(os.path.join(args.dst, camera, name), to_bgr(y, cb, cr))


if __name__ == "__main__":
    main()
