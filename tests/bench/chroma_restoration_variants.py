#!/usr/bin/python3
"""Copies of a 4:2:0 sequence with the chroma restoration's variants that were tried and not
kept (docs/notes/issue12_jpeg_chroma.md, "The restoration along the isophote, and kept off hue
edges"). The restoration itself is chroma_luma_guided.py's (--degree 3 --tau 0.1, the C++
defaults without isophote averaging or the hue-slope blend); the frames are written as PNG, to
be measured as 4:4:4.

Usage: /usr/bin/python3 tests/bench/chroma_restoration_variants.py SRC DST MODE [ARGS]
  fuse SY SB      each pixel's chroma the inverse-variance mean of the restored one (variance:
                  the windows' weighted misfit plus (dC/dY)²·SY², SY the luma noise in codes) and
                  the decoded one (variance: the squared change the codec's chroma path makes to
                  the restored chroma, plus SB²)
  backproject N   N rounds of restored += decoded − path(restored), so that the codec's chroma
                  path maps the result onto the decoded planes
  smooth SIGMA [S0]
                  the polynomial reads the luma blurred by an isotropic Gaussian of SIGMA px;
                  with S0, blended with the decoded chroma as edge.chroma_restoration_hue_slope
                  does (w = S0² / (S0² + |dC/dY|²))
"""
import os
import sys

import cv2
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..",
                                "scripts", "pbr"))
import jpeg_variants as jv  # noqa: E402
import pbr_common as pc  # noqa: E402
from chroma_luma_guided import fit_planes  # noqa: E402


def restore_planes(bgr, smooth_sigma=0.0):
    """Luma, and per chroma plane the decoded and restored chroma, the polynomial's slope dC/dY
    and the windows' weighted misfit (codes²)."""
    y, cb, cr = jv.to_ycbcr(bgr.astype(np.float64))
    read = cv2.GaussianBlur(y, (0, 0), smooth_sigma) if smooth_sigma > 0 else y
    t = (read - 128.0) / 64.0
    planes = []
    for c, (features, a, b, misfit) in zip((cb, cr), fit_planes(read, (cb, cr), 3, 4.0, 3, 0.1)):
        planes.append(dict(decoded=c, restored=sum(a_k * f_k for a_k, f_k in zip(a, features)) + b,
                           slope=sum(a[k] * (k + 1) * t ** k / 64.0 for k in range(len(a))),
                           misfit=misfit))
    return y, planes


def variant(bgr, mode, args):
    y, planes = restore_planes(bgr, float(args[0]) if mode == "smooth" else 0.0)
    out = []
    for p in planes:
        if mode == "fuse":
            sy, sb = float(args[0]), float(args[1])
            var_restored = p["misfit"] + p["slope"] ** 2 * sy ** 2
            var_decoded = (p["restored"] - jv.subsample(p["restored"])) ** 2 + sb ** 2
            w = var_decoded / (var_decoded + var_restored)
            out.append(w * p["restored"] + (1 - w) * p["decoded"])
        elif mode == "backproject":
            r = p["restored"]
            for _ in range(int(args[0])):
                r = r + (p["decoded"] - jv.subsample(r))
            out.append(r)
        elif mode == "smooth":
            out.append(p["restored"])
            if len(args) > 1:
                s0 = float(args[1])
                slope2 = planes[0]["slope"] ** 2 + planes[1]["slope"] ** 2
                w = s0 ** 2 / (s0 ** 2 + slope2)
                out[-1] = w * p["restored"] + (1 - w) * p["decoded"]
        else:
            sys.exit(f"unknown mode {mode}\n\n{__doc__}")
    return jv.to_bgr(y, out[0], out[1])


def main():
    if len(sys.argv) < 5:
        sys.exit(__doc__)
    src, dst, mode, args = sys.argv[1], sys.argv[2], sys.argv[3], sys.argv[4:]
    cameras = pc.copy_sequence_without_frames(src, dst)
    for camera in cameras:
        for name in sorted(os.listdir(os.path.join(src, camera))):
            stem, ext = os.path.splitext(name)
            if ext.lower() not in (".png", ".jpg", ".jpeg"):
                continue
            image = cv2.imread(os.path.join(src, camera, name))
            cv2.imwrite(os.path.join(dst, camera, stem + ".png"), variant(image, mode, args))


if __name__ == "__main__":
    main()
