#!/usr/bin/python3
"""A copy of a PNG sequence passed through a model of a baseline JPEG encoder, decoded two ways.

Usage: /usr/bin/python3 tests/bench/jpeg_tv_decode.py SRC DST plain|tv [--sampling 444|420]
                                                      [--quality 90] [--iters 20]

The encoder is jpeg_variants.py's: JFIF YCbCr of the codes, for 420 Cb and Cr averaged over
2x2 pixels, then 8x8 DCTs quantised with libjpeg's standard tables scaled to --quality.
- plain: decoded as libjpeg does: every coefficient at the centre of its quantisation interval,
  for 420 the chroma brought back by libjpeg's fancy upsampling;
- tv: the image with the smallest vectorial total variation (Y, Cb and Cr gradients under one
  norm, smoothed by 1 code) whose coefficients lie in the file's quantisation intervals, found
  by alternating a gradient step on the total variation with the projection onto those
  intervals (for 420 the chroma's constraint is on its 2x2 means, whose projection adds the
  same correction to the four pixels of a mean), --iters times, in the object's box (SRC's
  gt/mask grown by 32 px; outside it, plain). The box stands in for what a decoder would know
  from the predicted pose.
The frames stay PNG files; annotate them with `--set edge.chroma_sampling=4:4:4` (or 4:2:0 to
run the chroma correction on the plain 420 decode) and score them with pbr_errors
(docs/notes/issue12_jpeg_chroma.md, "Decoding the quantisation away").
"""
import argparse
import os
import sys

import cv2
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..",
                                "scripts", "pbr"))
import jpeg_variants as jv  # noqa: E402
import pbr_common as pc  # noqa: E402

# The orthonormal 8-point DCT-II matrix (cv2.dct's transform of an 8x8 block is D·X·Dᵀ).
DCT = np.array([[(np.sqrt(1 / 8) if k == 0 else np.sqrt(2 / 8)) *
                 np.cos(np.pi * (2 * n + 1) * k / 16) for n in range(8)] for k in range(8)])


def dct_blocks(x):
    h, w = x.shape
    b = x.reshape(h // 8, 8, w // 8, 8).transpose(0, 2, 1, 3)
    return np.einsum("ij,abjk,lk->abil", DCT, b, DCT)


def idct_blocks(d):
    b = np.einsum("ji,abjk,kl->abil", DCT, d, DCT)
    nh, nw = b.shape[:2]
    return b.transpose(0, 2, 1, 3).reshape(nh * 8, nw * 8)


def gradient(z):
    gx, gy = np.zeros_like(z), np.zeros_like(z)
    gx[:, :-1] = z[:, 1:] - z[:, :-1]
    gy[:-1, :] = z[1:, :] - z[:-1, :]
    return gx, gy


def divergence(px, py):
    d = np.zeros_like(px)
    d[:, :-1] += px[:, :-1]
    d[:, 1:] -= px[:, :-1]
    d[:-1, :] += py[:-1, :]
    d[1:, :] -= py[:-1, :]
    return d


class Channel:
    """One channel's quantised coefficients; `factor` 2 for a chroma plane of a 420 file."""

    def __init__(self, values, table, factor):
        self.table, self.factor = table, factor
        plane = jv.mean2x2(values) if factor == 2 else values
        self.coefficients = np.round(dct_blocks(plane - 128.0) / table)

    def plain(self):
        plane = idct_blocks(self.coefficients * self.table) + 128.0
        return jv.fancy_upsample(plane) if self.factor == 2 else plane

    def project(self, values, box):
        """The nearest values (in the box, full resolution) whose coefficients lie in the
        intervals."""
        y0, y1, x0, x1 = box
        f = self.factor
        c = self.coefficients[y0 // (8 * f):y1 // (8 * f), x0 // (8 * f):x1 // (8 * f)]
        low, high = (c - 0.5) * self.table, (c + 0.5) * self.table
        plane = jv.mean2x2(values) if f == 2 else values
        projected = idct_blocks(np.clip(dct_blocks(plane - 128.0), low, high)) + 128.0
        if f == 1:
            return projected
        return values + np.repeat(np.repeat(projected - plane, 2, 0), 2, 1)


def tv_decode(channels, planes, box, iters, step=0.2, smoothing=1.0):
    y0, y1, x0, x1 = box
    z = [p[y0:y1, x0:x1].copy() for p in planes]
    for _ in range(iters):
        g = [gradient(c) for c in z]
        norm = np.sqrt(sum(gx * gx + gy * gy for gx, gy in g) + smoothing * smoothing)
        z = [c + step * divergence(gx / norm, gy / norm) for c, (gx, gy) in zip(z, g)]
        z = [ch.project(c, box) for ch, c in zip(channels, z)]
    out = [p.copy() for p in planes]
    for o, c in zip(out, z):
        o[y0:y1, x0:x1] = c
    return out


def object_box(mask, shape, block):
    ys, xs = np.nonzero(mask)
    h, w = shape
    return (max(0, (ys.min() - 32) // block * block), min(h, (ys.max() + 32 + block) // block * block),
            max(0, (xs.min() - 32) // block * block), min(w, (xs.max() + 32 + block) // block * block))


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("src")
    parser.add_argument("dst")
    parser.add_argument("mode", choices=["plain", "tv"])
    parser.add_argument("--sampling", choices=["444", "420"], default="444")
    parser.add_argument("--quality", type=int, default=90)
    parser.add_argument("--iters", type=int, default=20)
    parser.add_argument("--smoothing", type=float, default=1.0,
                        help="codes: gradients below it are penalised quadratically (Huber-like)")
    args = parser.parse_args()
    factor = 2 if args.sampling == "420" else 1
    luma_table = jv.scaled_table(jv.LUMINANCE_TABLE, args.quality)
    chroma_table = jv.scaled_table(jv.CHROMINANCE_TABLE, args.quality)
    cameras = pc.copy_sequence_without_frames(args.src, args.dst)
    for camera in cameras:
        for name in sorted(os.listdir(os.path.join(args.src, camera))):
            image = cv2.imread(os.path.join(args.src, camera, name))
            if image.shape[0] % (8 * factor) or image.shape[1] % (8 * factor):
                raise SystemExit(f"{name}: size not a multiple of {8 * factor}")
            y, cb, cr = jv.to_ycbcr(image)
            channels = [Channel(y, luma_table, 1), Channel(cb, chroma_table, factor),
                        Channel(cr, chroma_table, factor)]
            planes = [ch.plain() for ch in channels]
            if args.mode == "tv":
                mask = cv2.imread(os.path.join(args.src, "gt", "mask", camera, name),
                                  cv2.IMREAD_UNCHANGED)
                planes = tv_decode(channels, planes, object_box(mask, y.shape, 8 * factor),
                                   args.iters, smoothing=args.smoothing)
            cv2.imwrite(os.path.join(args.dst, camera, name), jv.to_bgr(*planes))


if __name__ == "__main__":
    main()
