"""Sensor model and contract output of the physically based render path (issue 12).

Run by scripts/pbr_synth.sh after Blender (system Python with NumPy and OpenCV):
  /usr/bin/python3 scripts/pbr/postprocess.py --spec SPEC --raw OUT/raw --out OUT [--set k=v ...]
Reads Blender's scene-linear, unclipped beauty renders (OpenEXR), applies the lens blur
(Gaussian, sensor.lens_blur_px), Gaussian + shot noise (seeded per frame and camera), and only
then clips to the sensor's full scale and encodes sRGB 8-bit (a camera's optics blur the light
before its pixels saturate: clipping last moves a saturated surface's blurred edge towards the
darker side, as in real images); writes <camera>/NNNNNN.png (or .jpg, 4:2:0, when
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


def srgb_encode(v):
    v = np.clip(v, 0.0, 1.0)
    return np.where(v <= 0.0031308, 12.92 * v, 1.055 * np.power(v, 1 / 2.4) - 0.055)


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
    for ci, c in enumerate(plan["cameras"]):
        for k in range(plan["frames"]):
            lin = read_linear(os.path.join(args.raw, c["name"], f"{k:06d}.exr"))
            if lin.shape[2] == 4:  # window at full quality over the upsampled background
                bg = read_linear(os.path.join(args.raw, "bg", c["name"], f"{k:06d}.exr"))
                bg = cv2.resize(bg, (lin.shape[1], lin.shape[0]), interpolation=cv2.INTER_LINEAR)
                inside = lin[:, :, 3:4] > 0.5
                lin = np.where(inside, lin[:, :, :3], bg[:, :, :3])
            if se["lens_blur_px"] > 0:
                lin = cv2.GaussianBlur(lin, (0, 0), float(se["lens_blur_px"]),
                                       borderType=cv2.BORDER_REFLECT)
            rng = np.random.default_rng([int(spec["seed"]), 7001, ci, k])
            sigma = np.sqrt(se["noise_sigma"] ** 2 + se["shot_noise_gain"] * np.maximum(lin, 0))
            lin = lin + sigma * rng.standard_normal(lin.shape)
            img8 = np.round(srgb_encode(lin) * 255.0).astype(np.uint8)
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


main()
