"""Compares two dumps of docs/notes/patches/issue19_edge_fit_dump.cc (the same profiles fitted
by two builds): where both fits are found, the largest and mean differences of mu, sigma and w;
the profiles only one finds; and the mean |mu error| and sigma of each group.

Usage: /usr/bin/python3 docs/notes/patches/issue19_edge_fit_compare.py OLD NEW
"""
import sys

import numpy as np


def load(path):
    rows = np.loadtxt(path)
    return rows[:, 1], rows[:, 2].astype(bool), rows[:, 3], rows[:, 4], rows[:, 5]


truth, found_old, mu_old, sigma_old, w_old = load(sys.argv[1])
truth_new, found_new, mu_new, sigma_new, w_new = load(sys.argv[2])
assert np.array_equal(truth, truth_new), "the dumps are not of the same profiles"
both = found_old & found_new
only_old = found_old & ~found_new
only_new = found_new & ~found_old
d_mu = np.abs(mu_old[both] - mu_new[both])
print(f"both {both.sum()}, only old {only_old.sum()}, only new {only_new.sum()}")
print(f"both: |d mu| mean {d_mu.mean():.2e} max {d_mu.max():.2e} px; "
      f"max relative d sigma {np.max(np.abs(sigma_old[both] - sigma_new[both]) / sigma_old[both]):.2e}; "
      f"max |d w| {np.max(np.abs(w_old[both] - w_new[both])):.2e} px")
for name, group, mu, sigma in [("both", both, mu_new, sigma_new),
                               ("only new", only_new, mu_new, sigma_new),
                               ("only old", only_old, mu_old, sigma_old)]:
    if group.any():
        print(f"{name}: mean |mu error| {np.mean(np.abs(mu[group] - truth[group])):.4f} px, "
              f"mean sigma {np.mean(sigma[group]):.4f} px, sigma > 0.5 / 1 px: "
              f"{np.sum(sigma[group] > 0.5)} / {np.sum(sigma[group] > 1.0)}")
