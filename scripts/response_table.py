#!/usr/bin/python3
"""Writes a camera response table for `edge.response: table` (docs/camera_response.md): the
linear value of each 8-bit code 0..255, one per line.

  scripts/response_table.py filmic OUT    # Blender's "Filmic" view (needs --with-blender)
  scripts/response_table.py gamma G OUT   # (code / 255)^G, e.g. to edit by hand
  scripts/response_table.py srgb OUT

filmic inverts Blender's Filmic view transform on the grey axis (R = G = B), read from the
blender package's OCIO files (scripts/pbr/postprocess.py, FilmicEncoder): what Blender writes
by default when a render is saved without switching its view transform to "Standard". Its
colour desaturation (a 3-D table) is not per channel and is left out; on the Cycles render of
docs/notes/issue12_response.md the grey-axis inverse removes the bias all the same.
"""
import os
import sys

import numpy as np


def filmic_inverse():
    sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "pbr"))
    from postprocess import FilmicEncoder  # noqa: E402 (needs numpy and OpenCV)

    encode = FilmicEncoder()
    # Scene-linear grey from 1e-7 to 16 (Filmic's display white is 0.18·2^6.5 ≈ 16.3), display
    # code of each, inverted by interpolation. Code 255 then decodes to 16, the full scale
    # edge.clip_level and edge.min_contrast are relative to (LinearTable divides by it).
    linear = np.concatenate([[0.0], np.logspace(-7.0, np.log10(16.0), 40000)])
    grey = np.repeat(linear[:, None], 3, axis=1)
    codes = encode(grey)[:, 1] * 255.0
    order = np.argsort(codes, kind="stable")
    return np.interp(np.arange(256), codes[order], linear[order])


def main(argv):
    if len(argv) == 3 and argv[1] in ("filmic", "srgb"):
        kind, out = argv[1], argv[2]
    elif len(argv) == 4 and argv[1] == "gamma":
        kind, out = "gamma", argv[3]
    else:
        sys.stderr.write(__doc__)
        return 2
    v = np.arange(256) / 255.0
    if kind == "filmic":
        table, note = filmic_inverse(), "Blender's Filmic view transform (grey axis), inverted"
    elif kind == "srgb":
        table = np.where(v <= 0.04045, v / 12.92, ((v + 0.055) / 1.055) ** 2.4)
        note = "sRGB (IEC 61966-2-1) decoding"
    else:
        gamma = float(argv[2])
        table, note = v ** gamma, f"(code / 255)^{gamma}"
    with open(out, "w") as f:
        f.write(f"# linear value of codes 0..255: {note}\n")
        f.writelines(f"{value:.9g}\n" for value in table)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
