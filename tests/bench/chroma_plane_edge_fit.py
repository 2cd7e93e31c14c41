#!/usr/bin/python3
"""Edge lines measured on a 4:2:0 frame's own planes (full-resolution luma, half-resolution
chroma) through a model of the encoder, against the same fit on the PNG and on the decode.

Usage: /usr/bin/python3 tests/bench/chroma_plane_edge_fit.py SRC DUMP [--frames 10] [--every 3]
           [--half-length 1.5] [--reach 3.5] [--out FILE]

SRC is a PNG sequence (scripts/pbr_synth.sh); DUMP the `edge_bias_probe --dump` of it at the true
pose, whose lines (camera, frame, rim, centre, normal; s = 0 at the true contour) are measured
again here. Each frame is encoded as jpeg_variants.py models 4:2:0 without quantisation: JFIF
Y'CbCr of the codes, Cb and Cr averaged over 2x2 pixels. One model is fitted per line, a
straight edge through the line's centre along its normal blurred by a Gaussian between two
linear colours, rgb(s) = A + (B − A)·Φ((s − μ)/w) (8 parameters), sRGB-encoded to codes and
clipped to [0, 255] as the camera clips. Its data are the pixels within --half-length px of the
line along it and --reach px across it, three ways:
- png:    the PNG's codes, R'G'B' per pixel (the reference);
- decode: the codes decoded as libjpeg decodes 4:2:0 (chroma brought back by fancy upsampling),
          R'G'B' per pixel: what a fit of the decoded image sees, with no correction;
- planes: the encoder's planes themselves: Y' per pixel against the model's Y', and each 2x2
          chroma mean whose four pixels lie in the window against the mean of the model's Cb,
          Cr over those four pixels (weight 2: a mean of four), i.e. the codec's subsampling
          as part of the model instead of a correction after the fit.
Prints per camera and rim the mean and median μ (px, + outward) of each, over the lines all
three fit.
"""
import argparse
import os
import sys

import cv2
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..",
                                "scripts", "pbr"))
import jpeg_block_edge_fit as jb  # noqa: E402  (phi, lm)
import jpeg_variants as jv  # noqa: E402
import pbr_common as pc  # noqa: E402

YCC = jb.YCC


def codes_rgb(p, s):
    """Model R'G'B' codes at signed distances s for p = [mu, log w, A rgb, B rgb]."""
    w = np.exp(np.clip(p[1], -3.0, 2.0))
    c = jb.phi((s - p[0]) / w)[..., None]
    lin = p[2:5] + (p[5:8] - p[2:5]) * c
    return 255.0 * pc.srgb_encode(lin)


def ycc(rgb):
    return rgb @ YCC.T + np.array([0.0, 128.0, 128.0])


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("src")
    parser.add_argument("dump")
    parser.add_argument("--frames", type=int, default=10)
    parser.add_argument("--every", type=int, default=3)
    parser.add_argument("--half-length", type=float, default=1.5)
    parser.add_argument("--reach", type=float, default=3.5)
    parser.add_argument("--out")
    args = parser.parse_args()
    lines = {}
    with open(args.dump) as f:
        for k, row in enumerate(f):
            v = row.split()
            if int(v[1]) >= args.frames or k % args.every:
                continue
            lines.setdefault((v[0], int(v[1])), []).append(
                (v[2], np.array([float(v[3]), float(v[4])]), np.array([float(v[5]), float(v[6])])))
    rows = []
    steps = [1e-3, 1e-3] + [1e-4] * 6
    for (camera, frame), items in sorted(lines.items()):
        names = sorted(os.listdir(os.path.join(args.src, camera)))
        bgr = cv2.imread(os.path.join(args.src, camera, names[frame])).astype(float)
        rgb = bgr[..., ::-1]
        planes = ycc(rgb)
        half_cb, half_cr = jv.mean2x2(planes[..., 1]), jv.mean2x2(planes[..., 2])
        decoded = jv.to_bgr(planes[..., 0], jv.subsample(planes[..., 1]),
                            jv.subsample(planes[..., 2])).astype(float)[..., ::-1]
        h, w = planes.shape[:2]
        for rim, centre, normal in items:
            tangent = np.array([-normal[1], normal[0]])
            r = int(np.ceil(args.reach + args.half_length)) + 2
            x0, y0 = int(round(centre[0])) - r, int(round(centre[1])) - r
            x0 -= x0 % 2
            y0 -= y0 % 2
            if x0 < 0 or y0 < 0 or x0 + 2 * r + 2 > w or y0 + 2 * r + 2 > h:
                continue
            ys, xs = np.mgrid[y0:y0 + 2 * r + 2, x0:x0 + 2 * r + 2]
            d = np.stack([xs - centre[0], ys - centre[1]], -1)
            s, t = d @ normal, d @ tangent
            inside_window = (np.abs(s) <= args.reach) & (np.abs(t) <= args.half_length)
            if inside_window.sum() < 8:
                continue
            sw = s[inside_window]
            # 2x2 blocks all four of whose pixels lie in the window.
            block_in = inside_window.reshape(r + 1, 2, r + 1, 2).all((1, 3))
            block_s = s.reshape(r + 1, 2, r + 1, 2).transpose(0, 2, 1, 3).reshape(r + 1, r + 1, 4)
            bs = block_s[block_in]
            cb_obs = half_cb[y0 // 2:y0 // 2 + r + 1, x0 // 2:x0 // 2 + r + 1][block_in]
            cr_obs = half_cr[y0 // 2:y0 // 2 + r + 1, x0 // 2:x0 // 2 + r + 1][block_in]
            y_obs = planes[ys[inside_window], xs[inside_window], 0]
            fits = {}
            for kind, image in (("png", rgb), ("decode", decoded)):
                obs = image[ys[inside_window], xs[inside_window]]
                inner, outer = obs[sw < -1.5], obs[sw > 1.5]
                if len(inner) < 2 or len(outer) < 2:
                    break
                p0 = [0.0, np.log(0.7), *pc.srgb_to_linear(inner.mean(0)),
                      *pc.srgb_to_linear(outer.mean(0))]

                def residual(p, obs=obs):
                    return (codes_rgb(p, sw) - obs).ravel()

                fits[kind], _ = jb.lm(residual, p0, steps, watch=0)
                if kind == "png":
                    p_start = p0
            if len(fits) < 2 or len(bs) < 2:
                continue

            def plane_residual(p):
                model_y = ycc(codes_rgb(p, sw))[:, 0]
                model_c = ycc(codes_rgb(p, bs)).mean(1)  # (blocks, 3): the 2x2 means
                return np.concatenate([model_y - y_obs, 2.0 * (model_c[:, 1] - cb_obs),
                                       2.0 * (model_c[:, 2] - cr_obs)])

            fits["planes"], _ = jb.lm(plane_residual, p_start, steps, watch=0)
            decoded_obs = decoded[ys[inside_window], xs[inside_window]]

            def decode_residual(p):
                full = ycc(codes_rgb(p, s))  # the whole grid, 2 px beyond the window
                cb_up = jv.fancy_upsample(jv.mean2x2(full[..., 1]))
                cr_up = jv.fancy_upsample(jv.mean2x2(full[..., 2]))
                model = jv.to_bgr_float(full[..., 0], cb_up, cr_up)[..., ::-1]
                return (np.clip(model[inside_window], 0.0, 255.0) - decoded_obs).ravel()

            fits["codec"], _ = jb.lm(decode_residual, p_start, steps, watch=0)
            rows.append((camera, frame, rim, fits["png"][0], fits["decode"][0], fits["planes"][0],
                         fits["codec"][0]))
    if args.out:
        with open(args.out, "w") as f:
            for row in rows:
                f.write(" ".join(str(v) for v in row) + "\n")
    print(f"{args.src}: {len(rows)} lines; mean / median μ (px, + outward)")
    print("| camera | rim | lines | png | decode | planes | codec | mean \\|Δ\\| decode / planes / codec |")
    print("|---|---|---:|---|---|---|---|---|")
    for camera in sorted({r[0] for r in rows}):
        for rim in ["up", "down", "left", "right", "all"]:
            sel = np.array([r[3:] for r in rows if r[0] == camera and (rim == "all" or r[2] == rim)])
            if len(sel) == 0:
                continue
            sel = sel[np.all(np.abs(sel) < 2.5, axis=1)]
            cells = " | ".join(f"{np.mean(sel[:, k]):+.3f} / {np.median(sel[:, k]):+.3f}"
                               for k in range(4))
            diffs = " / ".join(f"{np.mean(np.abs(sel[:, k] - sel[:, 0])):.3f}" for k in (1, 2, 3))
            print(f"| {camera} | {rim} | {len(sel)} | {cells} | {diffs} |")


if __name__ == "__main__":
    main()
