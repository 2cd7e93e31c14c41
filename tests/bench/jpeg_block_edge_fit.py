#!/usr/bin/python3
"""Edge localisation through a model of the JPEG codec, against a fit of the decoded pixels.

Usage: /usr/bin/python3 tests/bench/jpeg_block_edge_fit.py SRC [--sampling 444|420]
           [--quality 90] [--frames 10] [--dump FILE]

SRC is a PNG sequence with gt/mask (scripts/pbr_synth.sh, or coverage_sequence.py's copy of
one). Each frame passes through jpeg_variants.py's model of a baseline encoder (JFIF YCbCr, for
420 Cb and Cr averaged over 2x2 pixels, 8x8 DCTs quantised with libjpeg's standard tables at
--quality), as jpeg_tv_decode.py does. In every coding unit (8x8 px for 444, a 16x16 px MCU for
420) that the object's true contour crosses once as a nearly straight line, one model is fitted
three ways: a straight edge blurred by a Gaussian between two linear colours,
rgb(x) = A + (B - A)·Φ((n·x - d)/w), sRGB-encoded to codes (9 parameters: the normal's angle, d,
w, A, B).
- png:   to the frame's own codes (no codec): the floor;
- plain: to the codes decoded as libjpeg decodes them (each coefficient at the centre of its
         interval, for 420 fancy upsampling), least squares over the pixels: what any fit of a
         decoded image does;
- codec: through the encoder: the model's codes to YCbCr (420: chroma 2x2 means) and 8x8 DCTs,
         against the file's dequantised coefficients, each residual weighted by
         1 / sqrt(s² + q²/12): s the sensor noise of that channel in that transform (estimated
         per unit from the png fit's residuals), q²/12 the variance of rounding to a multiple of
         q. This is the generalised least-squares fit of the edge to what the file holds.
Every fit starts at the true line (the fit of the same step to the coverage mask) with colours
from the unit's pixels clearly inside and outside. The error of a fit is the signed distance
(+ outward) from the true line to the fitted one, along the true normal, at the unit's centre.
Prints per rim direction (the outward normal's side) the number of units and each fit's mean
signed and mean absolute error (px); --dump writes one line per unit.
"""
import argparse
import os
import sys

import cv2
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..",
                                "scripts", "pbr"))
import jpeg_tv_decode as tv  # noqa: E402
import jpeg_variants as jv  # noqa: E402
import pbr_common as pc  # noqa: E402

SQRT2 = np.sqrt(2.0)
# JFIF's RGB -> YCbCr rows (R, G, B).
YCC = np.array([[0.299, 0.587, 0.114], [-0.168736, -0.331264, 0.5], [0.5, -0.418688, -0.081312]])


def phi(t):
    """The standard normal CDF (erf by Abramowitz & Stegun 7.1.26, |error| < 1.5e-7)."""
    z = np.abs(t) / SQRT2
    k = 1.0 / (1.0 + 0.3275911 * z)
    poly = k * (0.254829592 + k * (-0.284496736 + k * (1.421413741 + k * (-1.453152027
                                                                          + k * 1.061405429))))
    erf = 1.0 - poly * np.exp(-z * z)
    return 0.5 * (1.0 + np.sign(t) * erf)


def log_phi(t):
    """log Φ(t), with the asymptotic series in the lower tail."""
    t = np.asarray(t, float)
    tail = t < -5.0
    safe = np.where(tail, -5.0, t)
    out = np.log(np.maximum(phi(safe), 1e-300))
    tt = np.where(tail, t, -5.0)
    asymptotic = (-0.5 * tt * tt - np.log(-tt) - 0.5 * np.log(2 * np.pi)
                  + np.log1p(-1.0 / (tt * tt) + 3.0 / tt ** 4))
    return np.where(tail, asymptotic, out)


def interval_residual(model, centre, q, s):
    """Signed sqrt(2·(−log P + log P_max)), P = P(the true coefficient, model + N(0, s²), lies in
    [centre − q/2, centre + q/2]): the exact likelihood of a rounded coefficient under Gaussian
    noise, as a least-squares residual (0 at the centre, quadratic near it for s >> q, flat
    inside the interval and steep outside it for s << q)."""
    delta = np.abs(model - centre)
    a, b = (0.5 * q - delta) / s, (-0.5 * q - delta) / s
    la, lb = log_phi(a), log_phi(b)
    log_p = la + np.log1p(-np.minimum(np.exp(lb - la), 1 - 1e-16))
    a0, b0 = 0.5 * q / s, -0.5 * q / s
    log_pmax = log_phi(a0) + np.log1p(-np.minimum(np.exp(log_phi(b0) - log_phi(a0)), 1 - 1e-16))
    return np.sign(model - centre) * np.sqrt(np.maximum(2.0 * (log_pmax - log_p), 0.0))


def lm(residual, p0, steps, iters=40, watch=1):
    """Levenberg-Marquardt with central-difference Jacobians; stops when the cost or parameter
    `watch` (the edge's offset) no longer moves; returns (p, converged)."""
    p = np.array(p0, float)
    r = residual(p)
    cost = r @ r
    lam = 1e-3
    for _ in range(iters):
        jac = np.empty((r.size, p.size))
        for k, h in enumerate(steps):
            e = np.zeros_like(p)
            e[k] = h
            jac[:, k] = (residual(p + e) - residual(p - e)) / (2 * h)
        g = jac.T @ r
        hess = jac.T @ jac
        improved = False
        for _ in range(10):
            delta = -np.linalg.solve(hess + lam * np.diag(np.diag(hess) + 1e-12), g)
            r_new = residual(p + delta)
            cost_new = r_new @ r_new
            if cost_new < cost:
                p, r, lam, improved = p + delta, r_new, max(lam / 3, 1e-9), True
                break
            lam *= 4
        if not improved:
            return p, True
        if abs(cost - cost_new) < 1e-10 * max(cost, 1e-12) or abs(delta[watch]) < 1e-6:
            cost = cost_new
            return p, True
        cost = cost_new
    return p, False


class Unit:
    """One coding unit: its pixel centres relative to the unit's centre."""

    def __init__(self, size):
        self.size = size
        j, i = np.meshgrid(np.arange(size), np.arange(size))
        self.x = j + 0.5 - size / 2.0
        self.y = i + 0.5 - size / 2.0

    def s(self, theta, d):
        return np.cos(theta) * self.x + np.sin(theta) * self.y - d

    def codes(self, p):
        """Model BGR codes (size, size, 3) for p = [theta, d, log w, A rgb, B rgb] and, with
        21 parameters, each side's linear trend per channel (A_x, A_y, B_x, B_y rgb, per px)."""
        w = np.exp(np.clip(p[2], -3.0, 2.0))
        c = phi(self.s(p[0], p[1]) / w)[..., None]
        a, b = p[3:6], p[6:9]
        if len(p) == 21:
            x, y = self.x[..., None] / self.size, self.y[..., None] / self.size
            a = a + p[9:12] * x + p[12:15] * y
            b = b + p[15:18] * x + p[18:21] * y
        lin = a + (b - a) * c
        return 255.0 * pc.srgb_encode(lin)[..., ::-1]


def to_ycc(bgr):
    return np.einsum("ij,...j->...i", YCC, bgr[..., ::-1]) + np.array([0.0, 128.0, 128.0])


def truth_line(unit, m):
    """(theta, d) of the coverage mask's step in the unit, or None if it is not one straight
    step."""
    gy, gx = np.gradient(m)
    gsum = np.array([-gx.sum(), -gy.sum()])  # outward: where the coverage falls
    if np.linalg.norm(gsum) < 1e-6:
        return None
    theta = np.arctan2(gsum[1], gsum[0])
    band = (m > 0.02) & (m < 0.98)
    if band.sum() < 2:
        return None
    n = np.array([np.cos(theta), np.sin(theta)])
    d = (n[0] * unit.x[band] + n[1] * unit.y[band]).mean()

    def residual(p):
        return (1.0 - phi(unit.s(p[0], p[1]) / np.exp(p[2])) - m).ravel()

    p, ok = lm(residual, [theta, d, np.log(0.35)], [1e-4, 1e-4, 1e-3])
    rms = np.sqrt(np.mean(residual(p) ** 2))
    if not ok or rms > 0.03:
        return None
    return p[0], p[1]


def error_px(theta_t, d_t, theta_f, d_f):
    cosine = np.cos(theta_f - theta_t)
    return (d_f - d_t * cosine) / cosine


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("src")
    parser.add_argument("--sampling", choices=["444", "420"], default="444")
    parser.add_argument("--quality", type=int, default=90)
    parser.add_argument("--frames", type=int, default=10)
    parser.add_argument("--dump")
    parser.add_argument("--trends", action="store_true",
                        help="each side's colour a plane per channel (21 parameters)")
    args = parser.parse_args()
    factor = 2 if args.sampling == "420" else 1
    size = 8 * factor
    unit = Unit(size)
    q_luma = jv.scaled_table(jv.LUMINANCE_TABLE, args.quality)
    q_chroma = jv.scaled_table(jv.CHROMINANCE_TABLE, args.quality)
    cameras = sorted(os.listdir(os.path.join(args.src, "gt", "mask")))
    rows = []
    steps = [1e-4, 1e-3, 1e-3] + [1e-4] * (18 if args.trends else 6)
    extra = [0.0] * (12 if args.trends else 0)
    for camera in cameras:
        names = sorted(os.listdir(os.path.join(args.src, camera)))[:args.frames]
        for frame, name in enumerate(names):
            png = cv2.imread(os.path.join(args.src, camera, name)).astype(float)
            mask = cv2.imread(os.path.join(args.src, "gt", "mask", camera, f"{frame:06d}.png"),
                              cv2.IMREAD_UNCHANGED).astype(float) / 65535.0
            y, cb, cr = jv.to_ycbcr(png.astype(np.uint8))
            channels = [tv.Channel(y, q_luma, 1), tv.Channel(cb, q_chroma, factor),
                        tv.Channel(cr, q_chroma, factor)]
            decoded = jv.to_bgr(*[ch.plain() for ch in channels]).astype(float)
            dequantised = [ch.coefficients * ch.table for ch in channels]
            h, w = mask.shape
            for by in range(1, h // size - 1):
                for bx in range(1, w // size - 1):
                    sl = np.s_[by * size:(by + 1) * size, bx * size:(bx + 1) * size]
                    m = mask[sl]
                    if (m >= 0.999).sum() < size or (m <= 0.001).sum() < size:
                        continue
                    truth = truth_line(unit, m)
                    if truth is None:
                        continue
                    inside, outside = m >= 0.999, m <= 0.001
                    fits = {}
                    png_residual = None
                    for kind, image in (("png", png[sl]), ("plain", decoded[sl])):
                        lin = pc.srgb_to_linear(image)[..., ::-1]
                        p0 = [truth[0], truth[1], np.log(0.7), *lin[inside].mean(0),
                              *lin[outside].mean(0), *extra]

                        def residual(p, image=image):
                            return (unit.codes(p) - image).ravel()

                        p, _ = lm(residual, p0, steps)
                        fits[kind] = p
                        if kind == "png":
                            png_residual = (unit.codes(p) - image).reshape(-1, 3)
                    # Sensor noise per YCbCr channel from the png fit's residuals.
                    dof = png_residual.shape[0] * 3 / (png_residual.shape[0] * 3 - len(steps))
                    noise_var = np.var(to_ycc(png_residual[:, None, :])[:, 0, :], 0) * dof
                    noise_var[1:] /= factor * factor  # a 2x2 mean of independent noise
                    blocks_y = np.s_[by * factor:(by + 1) * factor, bx * factor:(bx + 1) * factor]
                    file_y = dequantised[0][blocks_y]
                    file_cb = dequantised[1][by, bx]
                    file_cr = dequantised[2][by, bx]
                    weight_y = 1.0 / np.sqrt(noise_var[0] + q_luma ** 2 / 12.0)
                    weight_cb = 1.0 / np.sqrt(noise_var[1] + q_chroma ** 2 / 12.0)
                    weight_cr = 1.0 / np.sqrt(noise_var[2] + q_chroma ** 2 / 12.0)

                    def codec_residual(p):
                        ycc = to_ycc(unit.codes(p))
                        ry = (tv.dct_blocks(ycc[..., 0] - 128.0) - file_y) * weight_y
                        cb_plane, cr_plane = ycc[..., 1], ycc[..., 2]
                        if factor == 2:
                            cb_plane, cr_plane = jv.mean2x2(cb_plane), jv.mean2x2(cr_plane)
                        rcb = (tv.dct_blocks(cb_plane - 128.0)[0, 0] - file_cb) * weight_cb
                        rcr = (tv.dct_blocks(cr_plane - 128.0)[0, 0] - file_cr) * weight_cr
                        return np.concatenate([ry.ravel(), rcb.ravel(), rcr.ravel()])

                    sd = np.sqrt(noise_var)

                    def interval_residuals(p):
                        ycc = to_ycc(unit.codes(p))
                        ry = interval_residual(tv.dct_blocks(ycc[..., 0] - 128.0), file_y,
                                               q_luma, sd[0])
                        cb_plane, cr_plane = ycc[..., 1], ycc[..., 2]
                        if factor == 2:
                            cb_plane, cr_plane = jv.mean2x2(cb_plane), jv.mean2x2(cr_plane)
                        rcb = interval_residual(tv.dct_blocks(cb_plane - 128.0)[0, 0], file_cb,
                                                q_chroma, sd[1])
                        rcr = interval_residual(tv.dct_blocks(cr_plane - 128.0)[0, 0], file_cr,
                                                q_chroma, sd[2])
                        return np.concatenate([ry.ravel(), rcb.ravel(), rcr.ravel()])

                    lin = pc.srgb_to_linear(decoded[sl])[..., ::-1]
                    p0 = [truth[0], truth[1], np.log(0.7), *lin[inside].mean(0),
                          *lin[outside].mean(0), *extra]
                    fits["codec"], _ = lm(codec_residual, p0, steps)
                    fits["interval"], _ = lm(interval_residuals, fits["codec"], steps)
                    n = np.array([np.cos(truth[0]), np.sin(truth[0])])
                    direction = ("left" if n[0] < 0 else "right") if abs(n[0]) > abs(n[1]) \
                        else ("up" if n[1] < 0 else "down")
                    errors = {k: error_px(truth[0], truth[1], p[0], p[1]) for k, p in fits.items()}
                    rows.append((camera, frame, by, bx, direction, errors["png"],
                                 errors["plain"], errors["codec"], errors["interval"],
                                 np.exp(fits["png"][2])))
    if args.dump:
        with open(args.dump, "w") as f:
            f.write("camera frame by bx direction png plain codec interval w_png\n")
            for r in rows:
                f.write(" ".join(str(v) for v in r) + "\n")
    kinds = ["png", "plain", "codec", "interval"]
    print(f"{args.src}: {args.sampling}, quality {args.quality}, {len(rows)} units")
    print("camera direction units | " + " | ".join(f"{k} signed / abs" for k in kinds))
    for camera in cameras + ["all"]:
        for direction in ["up", "down", "left", "right", "all"]:
            sel = [r for r in rows if (camera == "all" or r[0] == camera)
                   and (direction == "all" or r[4] == direction)]
            if not sel:
                continue
            e = np.array([r[5:9] for r in sel])
            e = e[np.all(np.abs(e) < 3, axis=1)]  # failed fits
            cells = " | ".join(f"{np.mean(e[:, k]):+.3f} / {np.mean(np.abs(e[:, k])):.3f}"
                               for k in range(4))
            print(f"{camera} {direction} {len(e)} | {cells}")


if __name__ == "__main__":
    main()
