"""Sensor model and contract output of the physically based render path (issue 12).

Run by scripts/pbr_synth.sh after Blender (system Python with NumPy and OpenCV):
  /usr/bin/python3 scripts/pbr/postprocess.py --spec SPEC --raw OUT/raw --out OUT [--set k=v ...]
Reads Blender's scene-linear, unclipped beauty renders (OpenEXR), applies the lens blur
(Gaussian, sensor.lens_blur_px), Gaussian + shot noise (seeded per frame and camera), and only
then clips to the sensor's full scale and encodes sRGB 8-bit (a camera's optics blur the light
before its pixels saturate: clipping last moves a saturated surface's blurred edge towards the
darker side, as in real images); sensor.view_transform "linear" writes the clipped values
linearly (a machine-vision camera with its gamma off), "filmic" maps the unclipped values
through Blender's Filmic view transform instead (its tone curve, as Blender's own file output
does by default; read from the blender package's OCIO files); writes <camera>/NNNNNN.png (or .jpg, 4:2:0, when
sensor.jpeg_quality > 0); writes the mask pass's alpha as 16-bit coverage gt/mask/<camera>/NNNNNN.png (65535 =
fully covered by the annotated object alone, unoccluded) and the contract files (rig.yaml,
object.yaml + model/, init_pose.txt, timestamps.csv, gt/ poses) from the same plan.
"""
import argparse
import json
import os
import sys

os.environ.setdefault("OPENCV_IO_ENABLE_OPENEXR", "1")  # before cv2 is imported
import cv2  # noqa: E402
import numpy as np  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import pbr_common as pc  # noqa: E402


def read_linear(path):
    """Blender's scene-linear beauty (OpenEXR, unclipped) as float64 BGR[A]."""
    image = cv2.imread(path, cv2.IMREAD_UNCHANGED)
    if image is None or image.dtype != np.float32 or image.ndim != 3:
        raise RuntimeError(f"{path}: missing or not a float OpenEXR image")
    return image.astype(np.float64)


# Blender's OCIO configuration (Debian package `blender`).
FILMIC_DIR = "/usr/share/blender/datafiles/colormanagement/filmic"
# Filmic Log's log2 allocation: scene-linear 2^-12.47... .. 2^12.52... onto [0, 1].
FILMIC_LOG2_MIN, FILMIC_LOG2_MAX = -12.473931188, 12.526068812


def read_spi1d(path):
    """(domain low, domain high, values) of an OCIO .spi1d LUT."""
    values, low, high, inside = [], 0.0, 1.0, False
    with open(path) as f:
        for line in f:
            fields = line.split()
            if not fields:
                continue
            if fields[0] == "From":
                low, high = float(fields[1]), float(fields[2])
            elif fields[0] in ("{", "}"):
                inside = fields[0] == "{"
            elif inside:
                values.append(float(fields[0]))
    return low, high, np.array(values)


def read_spi3d(path):
    """An OCIO .spi3d LUT as an n×n×n×3 array indexed by (R, G, B)."""
    with open(path) as f:
        lines = f.read().split("\n")
    n = int(lines[2].split()[0])
    lut = np.zeros((n, n, n, 3))
    for line in lines[3:]:
        fields = line.split()
        if len(fields) == 6:
            lut[int(fields[0]), int(fields[1]), int(fields[2])] = [float(v) for v in fields[3:]]
    return lut


def trilinear(lut, t):
    """`lut` (n×n×n×3) at t (...×3 in [0, 1]), trilinear."""
    n = lut.shape[0]
    p = np.clip(t, 0.0, 1.0) * (n - 1)
    i0 = np.minimum(np.floor(p).astype(int), n - 2)
    f = p - i0
    out = np.zeros(t.shape)
    for dr in (0, 1):
        for dg in (0, 1):
            for db in (0, 1):
                w = ((f[..., 0] if dr else 1 - f[..., 0]) * (f[..., 1] if dg else 1 - f[..., 1]) *
                     (f[..., 2] if db else 1 - f[..., 2]))
                out += w[..., None] * lut[i0[..., 0] + dr, i0[..., 1] + dg, i0[..., 2] + db]
    return out


class FilmicEncoder:
    """Blender's "Filmic" view on the sRGB display (config.ocio: Linear -> Filmic Log, i.e. the
    log2 allocation, filmic_desat65cube.spi3d and a uniform allocation [0, 0.66], then
    filmic_to_0-70_1-03.spi1d), applied to scene-linear RGB (the 3-D table trilinear, where
    OCIO's "best" interpolation is tetrahedral)."""

    def __init__(self, directory=FILMIC_DIR):
        cube = os.path.join(directory, "filmic_desat65cube.spi3d")
        curve = os.path.join(directory, "filmic_to_0-70_1-03.spi1d")
        for path in (cube, curve):
            if not os.path.exists(path):
                raise RuntimeError(f"{path}: missing (sensor.view_transform 'filmic' needs "
                                   "Blender's colour management files: scripts/setup.sh "
                                   "--with-blender)")
        self.cube = read_spi3d(cube)
        self.low, self.high, self.curve = read_spi1d(curve)

    def __call__(self, rgb):
        t = (np.log2(np.maximum(rgb, 2.0 ** FILMIC_LOG2_MIN)) - FILMIC_LOG2_MIN) / (
            FILMIC_LOG2_MAX - FILMIC_LOG2_MIN)
        v = trilinear(self.cube, t) / 0.66
        v = np.clip((v - self.low) / (self.high - self.low), 0.0, 1.0) * (len(self.curve) - 1)
        return np.clip(np.interp(v, np.arange(len(self.curve)), self.curve), 0.0, 1.0)


def encode_image(path, image8, jpeg_quality):
    if jpeg_quality > 0:
        # libjpeg's default chroma subsampling is 4:2:0 (OpenCV 4.6's Python binding has no
        # IMWRITE_JPEG_SAMPLING_FACTOR to ask for it explicitly).
        params = [cv2.IMWRITE_JPEG_QUALITY, int(jpeg_quality)]
        if hasattr(cv2, "IMWRITE_JPEG_SAMPLING_FACTOR"):
            params += [cv2.IMWRITE_JPEG_SAMPLING_FACTOR, cv2.IMWRITE_JPEG_SAMPLING_FACTOR_420]
        ok, data = cv2.imencode(".jpg", image8, params)
    else:
        ok, data = cv2.imencode(".png", image8)
    if not ok:
        raise RuntimeError(f"{path}: encoding failed")
    pc.write_atomic(path, data.tobytes())


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--spec", required=True)
    ap.add_argument("--raw", required=True)
    ap.add_argument("--out", required=True)
    ap.add_argument("--set", action="append", default=[])
    args = ap.parse_args()
    spec = pc.load_spec(args.spec, args.set)
    with open(os.path.join(args.raw, "plan.json")) as f:
        plan = json.load(f)
    se = spec["sensor"]
    ext = ".jpg" if se["jpeg_quality"] > 0 else ".png"
    if se["view_transform"] not in ("standard", "linear", "filmic"):
        raise ValueError(f"{args.spec}: sensor.view_transform must be standard, linear or filmic")
    filmic = FilmicEncoder() if se["view_transform"] == "filmic" else None
    for ci, c in enumerate(plan["cameras"]):
        for k in range(plan["frames"]):
            lin = read_linear(os.path.join(args.raw, c["name"], f"{k:06d}.exr"))
            if lin.shape[2] == 4:  # window at full quality over the upsampled background
                bg = read_linear(os.path.join(args.raw, "bg", c["name"], f"{k:06d}.exr"))
                bg = cv2.resize(bg, (lin.shape[1], lin.shape[0]), interpolation=cv2.INTER_LINEAR)
                inside = lin[:, :, 3:4] > 0.5
                lin = np.where(inside, lin[:, :, :3], bg[:, :, :3])
            lin = pc.apply_sensor(lin, se, np.random.default_rng([int(spec["seed"]), 7001, ci, k]))
            if se["view_transform"] == "linear":
                img8 = np.round(np.clip(lin, 0.0, 1.0) * 255.0).astype(np.uint8)
            elif filmic is None:
                img8 = np.round(pc.srgb_encode(lin) * 255.0).astype(np.uint8)
            else:  # BGR -> RGB for the LUT and back
                img8 = np.round(filmic(lin[:, :, ::-1])[:, :, ::-1] * 255.0).astype(np.uint8)
            encode_image(os.path.join(args.out, c["name"], f"{k:06d}{ext}"), img8,
                         se["jpeg_quality"])
            mask = cv2.imread(os.path.join(args.raw, "mask", c["name"], f"{k:06d}.png"),
                              cv2.IMREAD_UNCHANGED)
            if mask is None or mask.ndim != 3 or mask.shape[2] != 4:
                raise RuntimeError(f"{args.raw}/mask/{c['name']}/{k:06d}.png: missing or no alpha")
            ok, data = cv2.imencode(".png", np.ascontiguousarray(mask[:, :, 3]))
            pc.write_atomic(os.path.join(args.out, "gt", "mask", c["name"], f"{k:06d}.png"),
                            data.tobytes())
    pc.write_contract(plan, spec, args.out)
    timing_path = os.path.join(args.raw, "timing.json")
    if os.path.exists(timing_path):
        with open(timing_path) as f:
            timing = json.load(f)
        b, m = timing["beauty_s"], timing["mask_s"]
        summary = {"beauty_s_per_image": sum(b) / max(len(b), 1),
                   "mask_s_per_image": sum(m) / max(len(m), 1),
                   "images": len(b)}
        pc.write_atomic(os.path.join(args.out, "pbr_timing.json"), json.dumps(summary) + "\n")


if __name__ == "__main__":
    main()
