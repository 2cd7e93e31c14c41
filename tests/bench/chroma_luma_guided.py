#!/usr/bin/python3
"""A copy of a 4:2:0 sequence whose frames have their chroma brought back to full resolution by
the luma, which JPEG keeps at full resolution (the prototype of edge.chroma_restoration).

Usage: /usr/bin/python3 tests/bench/chroma_luma_guided.py SRC DST [--radius 3] [--eps 4]
           [--degree 1] [--tau 0] [--compare PNG_SEQ]

SRC's frames are 4:2:0 (JPEG files, or PNG copies made by jpeg_variants.py subsample). Where a
neighbourhood holds two colours, every pixel is a mix of them, so its chroma codes are a smooth
function of its luma codes (a colour line in linear light, bent by the sRGB curve), modelled as a
polynomial of --degree in f = (Y − 128) / 64. The codec's chroma path (2x2 means, libjpeg's fancy
upsampling) is linear, so the decoded chroma is the same polynomial of the features passed through
that path: C_decoded = Σ a_k·path(f^k) + b. Fitted by least squares in each (2r+1)² window (a
ridge --eps on the coefficients, in luma codes², keeps flat windows at their mean chroma) and
averaged over the windows that hold a pixel as the guided filter does, uniformly, or with --tau > 0
weighted by 1 / (window misfit + tau) (misfit: the window's mean squared chroma residual, codes²),
then applied to the pixel's own luma. The frames are written as PNG, so the edge stage reads them
as 4:4:4. `edge.chroma_restoration: true` is the C++ form of --degree 3 --tau 0.1
(include/bcot/core/chroma_restoration.h).

With --compare, prints the RMS difference in codes to the lossless twin's frames over the pixels
whose 3x3 neighbourhood holds a luma step of at least 8 codes (edges), for the decode and for the
restoration.
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


def box(image, radius):
    return cv2.blur(image, (2 * radius + 1, 2 * radius + 1), borderType=cv2.BORDER_REFLECT)


def fit_planes(read_luma, planes, radius, eps, degree, tau):
    """The polynomial in f = (read_luma − 128) / 64 fitted per window to each chroma plane through
    the codec's chroma path, averaged over the windows holding each pixel (uniformly, or with
    tau > 0 weighted by 1 / (misfit + tau)). Per plane: the features f^k, the averaged a_k and b,
    and the windows' averaged misfit (codes²; None when uniform)."""
    features = [((read_luma - 128.0) / 64.0) ** k for k in range(1, degree + 1)]
    paths = [jv.subsample(f) for f in features]  # each feature through the chroma's path
    means = [box(p, radius) for p in paths]
    k = len(features)
    cov_ff = np.empty(read_luma.shape + (k, k))
    for i in range(k):
        for j in range(k):
            cov_ff[..., i, j] = box(paths[i] * paths[j], radius) - means[i] * means[j]
    cov_ff += (eps / 4096.0) * np.eye(k)  # eps in codes² of Y
    fits = []
    for c in planes:
        mean_c = box(c, radius)
        cov_fc = np.stack([box(paths[i] * c, radius) - means[i] * mean_c for i in range(k)], -1)
        a = np.linalg.solve(cov_ff, cov_fc[..., None])[..., 0]
        b = mean_c - sum(a[..., i] * means[i] for i in range(k))
        if tau <= 0:
            fits.append((features, [box(a[..., i], radius) for i in range(k)], box(b, radius), None))
            continue
        # Each window's own misfit: its mean squared residual of the decoded chroma.
        resid = np.maximum(box(c * c, radius) - mean_c * mean_c - (a * cov_fc).sum(-1), 0.0)
        weight = 1.0 / (resid + tau)
        norm = box(weight, radius)
        fits.append((features, [box(weight * a[..., i], radius) / norm for i in range(k)],
                     box(weight * b, radius) / norm, box(weight * resid, radius) / norm))
    return fits


def restore(bgr, radius, eps, degree=1, tau=0.0):
    y, cb, cr = jv.to_ycbcr(bgr)
    out = [sum(a_i * f_i for a_i, f_i in zip(a, features)) + b
           for features, a, b, _ in fit_planes(y, (cb, cr), radius, eps, degree, tau)]
    return jv.to_bgr(y, out[0], out[1])


def edge_pixels(bgr):
    y = jv.to_ycbcr(bgr)[0].astype(np.float32)
    kernel = np.ones((3, 3), np.uint8)
    return (cv2.dilate(y, kernel) - cv2.erode(y, kernel)) >= 8


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("src")
    parser.add_argument("dst")
    parser.add_argument("--radius", type=int, default=3)
    parser.add_argument("--eps", type=float, default=4.0)
    parser.add_argument("--degree", type=int, default=1)
    parser.add_argument("--tau", type=float, default=0.0)
    parser.add_argument("--compare")
    args = parser.parse_args()
    cameras = pc.copy_sequence_without_frames(args.src, args.dst)
    sums = np.zeros(2)
    count = 0
    for camera in cameras:
        for name in sorted(os.listdir(os.path.join(args.src, camera))):
            stem, ext = os.path.splitext(name)
            if ext.lower() not in (".png", ".jpg", ".jpeg"):
                continue
            image = cv2.imread(os.path.join(args.src, camera, name))
            restored = restore(image, args.radius, args.eps, args.degree, args.tau)
            cv2.imwrite(os.path.join(args.dst, camera, stem + ".png"), restored)
            if args.compare:
                truth = cv2.imread(os.path.join(args.compare, camera, stem + ".png"))
                mask = edge_pixels(truth)
                for k, test in enumerate((image, restored)):
                    d = test.astype(float)[mask] - truth.astype(float)[mask]
                    sums[k] += (d * d).sum()
                count += 3 * int(mask.sum())
    if args.compare and count:
        rms = np.sqrt(sums / count)
        print(f"edge pixels: RMS to the lossless frames {rms[0]:.2f} codes (decoded), "
              f"{rms[1]:.2f} codes (restored)")


if __name__ == "__main__":
    main()
