"""Shared parts of the numpy refits of `edge_bias_probe --dump` lines (edge_rim_*_fit.py).

S: the probe's sample offsets; scalar_profile: the profile the edge stage fits, formed from a
line's linear RGB samples; edge_model: that stage's model (M0); levenberg_marquardt: the fit of
a profile model with a numerical Jacobian. Not a test.
"""
import math

import numpy as np

ERF = np.vectorize(math.erf)
SAMPLES = 33  # the probe's profile: -4 ... +4 px every 0.25 px
S = (np.arange(SAMPLES) - SAMPLES // 2) * 0.25


def cdf(z):
    """Phi(z), the standard normal distribution function."""
    return 0.5 * (1.0 + ERF(z / math.sqrt(2.0)))


def cdf_integral(z):
    """The integral of Phi: z Phi(z) + phi(z) (the Gaussian-blurred kink)."""
    return z * cdf(z) + np.exp(-z * z / 2.0) / math.sqrt(2.0 * math.pi)


def edge_model(p, s, mu0):
    """M0 of edge_lines.h at p = (a, g, b, mu, log w, k, ...): a + g (s - mu0) + b Phi(z) +
    k w R(z), z = (s - mu)/w; entries after the sixth are ignored."""
    a, g, b, mu, log_w, k = p[:6]
    w = math.exp(log_w)
    z = (s - mu) / w
    return a + g * (s - mu0) + b * cdf(z) + k * w * cdf_integral(z)


def scalar_profile(colors, s):
    """(y, mu0): the samples projected on the contrast direction of the unclipped channels
    (mean over s in [-4, -1] minus mean over [1, 4], channels below 0.95) and the steepest
    sample within 2 px; None when no channel has contrast."""
    inside = colors[(s >= -4) & (s <= -1)].mean(0)
    outside = colors[(s >= 1) & (s <= 4)].mean(0)
    direction = (inside - outside) * (colors.max(0) < 0.95)
    if np.linalg.norm(direction) < 1e-6:
        return None
    y = colors @ (direction / np.linalg.norm(direction))
    near = np.abs(s) <= 2.0
    return y, s[near][np.argmax(np.abs(np.gradient(y, s)[near]))]


def levenberg_marquardt(model, p, s, y, mu0):
    """Fits model(p, s) to y from p, whose entries 3 and 4 are mu and log w; the parameters, or
    None when mu moves more than 2 px from mu0 or w leaves (0.2, 3) px."""
    damping = 1e-3
    r = model(p, s) - y
    cost = r @ r
    for _ in range(60):
        jacobian = np.empty((len(s), len(p)))
        for j in range(len(p)):
            d = np.zeros_like(p)
            d[j] = 1e-6
            jacobian[:, j] = (model(p + d, s) - model(p - d, s)) / 2e-6
        normal = jacobian.T @ jacobian
        gradient = jacobian.T @ r
        step = np.zeros_like(p)
        while damping <= 1e8:
            step = np.linalg.solve(normal + damping * np.diag(np.diag(normal) + 1e-12), -gradient)
            trial = p + step
            if not -5.0 < trial[4] < 3.0:
                damping *= 4.0
                continue
            r_trial = model(trial, s) - y
            if r_trial @ r_trial < cost:
                p, r, cost = trial, r_trial, r_trial @ r_trial
                damping = max(damping / 3.0, 1e-9)
                break
            damping *= 4.0
        if damping > 1e8 or np.abs(step).max() < 1e-7:
            break
    if abs(p[3] - mu0) > 2.0 or not 0.2 < math.exp(p[4]) < 3.0:
        return None
    return p


def start(s, y, mu0, extra):
    """The start of a fit: levels inside and outside mu0, no trend, w = 0.7 px, `extra` zeros."""
    inside = y[s < mu0 - 0.5].mean() if np.any(s < mu0 - 0.5) else y[0]
    outside = y[s > mu0 + 0.5].mean() if np.any(s > mu0 + 0.5) else y[-1]
    return np.array([inside, 0.0, outside - inside, mu0, math.log(0.7), 0.0] + [0.0] * extra)


def print_bins(path, results, names):
    """Per (camera, bin) of `results` (lists of per-line mu tuples named by `names`), the count
    and the mean and median of each mu; then per camera the difference of the means up - down."""
    for (camera, direction), values in sorted(results.items()):
        v = np.array(values)
        print(f"{path} {camera} {direction:5s} n {len(v):4d} | "
              + " | ".join(f"{name} mean {v[:, c].mean():+.3f} median {np.median(v[:, c]):+.3f}"
                           for c, name in enumerate(names)))
    for camera in sorted({key[0] for key in results}):
        if (camera, "up") in results and (camera, "down") in results:
            up, down = np.array(results[(camera, "up")]), np.array(results[(camera, "down")])
            differences = " ".join(f"{name} {up[:, c].mean() - down[:, c].mean():+.3f}"
                                   for c, name in enumerate(names))
            print(f"{path} {camera} up - down: {differences}")
