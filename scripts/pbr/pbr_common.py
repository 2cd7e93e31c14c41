"""Shared by the physically based render path (issue 12): scene specs, the seeded scene plan
(rig, object trajectory, lights, clutter, distractors) and the sequence contract writers.

Pure Python + NumPy, so it runs both inside Blender (scripts/pbr/render_blender.py) and under
the system Python (scripts/pbr/postprocess.py). Conventions, as everywhere in bcot:
  * camera frame: OpenCV, x right, y down, z forward; pixel centres at integer coordinates;
  * poses: X_target = R·X_source + t, translations in mm;
  * the rig frame is the scene's world frame in mm (z up, the floor at z = 0); Blender gets
    the same frame in metres.
Not meant to be run by itself.
"""
import copy
import hashlib
import json
import math
import os
import shutil

import numpy as np

# Every key a scene spec may set, with its default. Paths are relative to the spec file.
DEFAULTS = {
    "name": "pbr",
    "seed": 1,
    "frames": 40,
    "fps": 30,
    "camera": {
        "width": 960, "height": 768, "f_px": 720.0, "fy_over_fx": 1.0,
        # principal point = image centre + this offset (px), so that a slip shows up
        "principal_offset_px": [4.25, -3.5],
        "included_angle_deg": 86.0,  # between the two optical axes (about the vertical)
        "azimuth_deg": 0.0,          # of the rig's bisector
        "elevation_deg": 18.0,       # cameras look down onto the object by this angle
        "distance_mm": 750.0,
        # further cameras (cam2, cam3, ...), each [azimuth_deg, elevation_deg] on the same
        # sphere about the target, e.g. [[0, 60]]: one above the ring, on the bisector
        "extra_views": [],
    },
    "object": {
        "mesh": "../../data/meshes/bunny.obj",
        "size_mm": 150.0,            # longest bounding-box side
        "material": "plastic",       # diffuse | plastic | glossy | metal | dark | bright
        "color_rgb": [200, 70, 45],  # sRGB 0..255 base colour
        # Faces meeting at more than this angle (deg) keep a sharp edge (a machined part's
        # creases); 180: every edge shaded smooth (interpolated normals), as for a curved object.
        "smooth_angle_deg": 180.0,
    },
    "motion": {
        "amplitude_mm": [60.0, 60.0, 40.0],     # of the bbox centre about the target point
        "rotation_deg_per_frame": 2.0,
        "lift_mm": 170.0,                       # target point above the table top
    },
    "init": {"rotation_deg": 5.0, "translation_mm": 5.0},
    "lights": {
        "key_elevation_deg": 50.0, "key_azimuth_deg": -30.0,
        "key_azimuth_end_deg": None,  # moving key light: azimuth at the last frame
        "key_power_w": 120.0, "key_size_m": 0.6, "key_distance_m": 1.6,
        "fill_ratio": 0.15,           # fill area light (opposite, low) power / key power
        "points": 2,                  # weak point lights at random places in the room
        "point_power_w": 15.0,
        "ambient": 0.05,              # world (sky) strength
    },
    "scene": {
        "room": True, "table": True,
        "clutter": 10,
        "distractors": True,          # one per camera, same material, touching in its image
        "distractor_overlap": 0.15,   # fraction of the distractor's image radius behind the object
        "occluder": False,            # a finger-like capsule in front of the object (cam0)
        "occluder_radius_mm": 9.0,    # its radius: 9 a finger, 20-25 two fingers or a thumb's base
        "occluder_length_mm": 80.0,
        "occluder_drop_mm": 55.0,     # how far below the object's centre it passes (cam0's image)
        "occluder_color_rgb": [224, 172, 140],  # skin; the object's colour makes it hardest
        "occluder_material": "diffuse",         # a material preset of object.material
        "occluder_between_cameras": False,      # in front of the rig's middle: in both images
        "occluder_distance_mm": 160.0,          # how far in front of the object it passes
    },
    "render": {
        # The beauty pass is rendered at `samples` in a window around the object and its
        # distractor (grown by roi_margin_px), and at background_samples and 1/background_scale
        # resolution (upsampled) elsewhere; roi_margin_px < 0: the whole image at `samples`.
        "roi_margin_px": 48, "background_scale": 4, "background_samples": 8,
        "samples": 32, "adaptive_threshold": 0.02, "max_bounces": 4,
        "mask_samples": 64,
        "dof_fstop": 0.0,             # > 0: depth of field focused on the target point
        "motion_blur_shutter": 0.0,   # > 0: motion blur, shutter in frames
        "exposure": 0.0,
    },
    "sensor": {
        "lens_blur_px": 0.6,          # Gaussian sigma after rendering, in linear light
        "noise_sigma": 0.004,         # Gaussian read noise (linear, 0..1)
        "shot_noise_gain": 0.002,     # variance += gain·value
        "jpeg_quality": 0,            # > 0: write 4:2:0 JPEG frames at this quality, else PNG
        "view_transform": "standard",  # standard: clip, sRGB | linear: clip, codes ∝ light | filmic: Blender's Filmic
    },
}


def deep_merge(base, override, where="spec"):
    out = copy.deepcopy(base)
    for key, value in override.items():
        if key not in out:
            raise ValueError(f"{where}: unknown key '{key}'")
        if isinstance(out[key], dict):
            if not isinstance(value, dict):
                raise ValueError(f"{where}.{key}: expected a mapping")
            out[key] = deep_merge(out[key], value, f"{where}.{key}")
        else:
            out[key] = value
    return out


def set_override(spec, assignment):
    """`section.key=value` (value parsed as JSON, else taken as a string)."""
    path, _, text = assignment.partition("=")
    try:
        value = json.loads(text)
    except ValueError:
        value = text
    node = spec
    keys = path.split(".")
    for key in keys[:-1]:
        if key not in node or not isinstance(node[key], dict):
            raise ValueError(f"--set {assignment}: unknown section '{key}'")
        node = node[key]
    if keys[-1] not in node:
        raise ValueError(f"--set {assignment}: unknown key '{keys[-1]}'")
    node[keys[-1]] = value


def load_spec(path, overrides=()):
    with open(path) as f:
        raw = json.load(f)
    spec = deep_merge(DEFAULTS, raw, os.path.basename(path))
    for assignment in overrides:
        set_override(spec, assignment)
    for view in spec["camera"]["extra_views"]:
        if (not isinstance(view, list) or len(view) != 2 or
                not all(isinstance(v, (int, float)) for v in view) or not -80.0 <= view[1] <= 80.0):
            raise ValueError(f"{path}: camera.extra_views entry {view}: must be "
                             "[azimuth_deg, elevation_deg] with the elevation in [-80, 80]")
    angle = spec["object"]["smooth_angle_deg"]
    if not isinstance(angle, (int, float)) or not 0.0 < angle <= 180.0:
        raise ValueError(f"{path}: object.smooth_angle_deg = {angle}, must be in (0, 180]")
    for key in ("occluder_radius_mm", "occluder_length_mm", "occluder_distance_mm"):
        value = spec["scene"][key]
        if not isinstance(value, (int, float)) or value <= 0.0:
            raise ValueError(f"{path}: scene.{key} = {value}, must be > 0")
    base = os.path.dirname(os.path.abspath(path))
    mesh = spec["object"]["mesh"]
    spec["object"]["mesh_path"] = mesh if os.path.isabs(mesh) else os.path.normpath(
        os.path.join(base, mesh))
    return spec


def spec_hash(spec, extra_files=()):
    h = hashlib.sha256(json.dumps(spec, sort_keys=True).encode())
    for path in extra_files:
        with open(path, "rb") as f:
            h.update(f.read())
    return h.hexdigest()[:12]


# ---------------------------------------------------------------------------------------------
# Geometry

def exp_so3(w):
    theta = float(np.linalg.norm(w))
    if theta < 1e-12:
        return np.eye(3)
    k = np.asarray(w, float) / theta
    K = np.array([[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]])
    return np.eye(3) + math.sin(theta) * K + (1 - math.cos(theta)) * K @ K


def nearest_rotation(m):
    u, _, vt = np.linalg.svd(m)
    r = u @ vt
    if np.linalg.det(r) < 0:
        u[:, -1] *= -1
        r = u @ vt
    return r


def iso(r, t):
    m = np.eye(4)
    m[:3, :3] = r
    m[:3, 3] = t
    return m


def look_at_cv(eye, target, up=(0.0, 0.0, 1.0)):
    """world_from_cam (OpenCV axes) of a camera at `eye` looking at `target`."""
    z = np.asarray(target, float) - np.asarray(eye, float)
    z /= np.linalg.norm(z)
    x = np.cross(z, np.asarray(up, float))
    x /= np.linalg.norm(x)
    y = np.cross(z, x)
    return iso(np.column_stack([x, y, z]), eye)


def unit_vector(rng):
    v = rng.normal(size=3)
    return v / np.linalg.norm(v)


def load_mesh_arrays(path):
    """Vertices (n×3, file units) and triangles (fan-triangulated) of an OBJ or OFF file."""
    verts, faces = [], []
    ext = os.path.splitext(path)[1].lower()
    with open(path) as f:
        if ext == ".obj":
            for line in f:
                parts = line.split()
                if not parts:
                    continue
                if parts[0] == "v":
                    verts.append([float(p) for p in parts[1:4]])
                elif parts[0] == "f":
                    idx = []
                    for p in parts[1:]:
                        i = int(p.split("/")[0])
                        idx.append(i - 1 if i > 0 else len(verts) + i)
                    faces.append(idx)
        elif ext == ".off":
            tokens = []
            for line in f:
                line = line.split("#")[0]
                tokens.extend(line.split())
            if tokens[0] != "OFF":
                raise ValueError(f"{path}: not an OFF file")
            nv, nf = int(tokens[1]), int(tokens[2])
            pos = 4
            for _ in range(nv):
                verts.append([float(t) for t in tokens[pos:pos + 3]])
                pos += 3
            for _ in range(nf):
                n = int(tokens[pos])
                faces.append([int(t) for t in tokens[pos + 1:pos + 1 + n]])
                pos += 1 + n
        else:
            raise ValueError(f"{path}: only .obj and .off meshes are supported")
    tris = []
    for face in faces:
        for k in range(1, len(face) - 1):
            tris.append([face[0], face[k], face[k + 1]])
    return np.array(verts, float), np.array(tris, int)


# ---------------------------------------------------------------------------------------------
# The scene plan: everything random is drawn here, from the spec's seed, in a fixed order.

MATERIALS = {
    # Principled BSDF inputs per preset (base colour comes from the spec or the clutter draw)
    "diffuse": {"Roughness": 0.9, "Specular": 0.3},
    "plastic": {"Roughness": 0.35, "Specular": 0.5, "Clearcoat": 0.3,
                "Clearcoat Roughness": 0.1},
    "glossy": {"Roughness": 0.15, "Specular": 0.7},
    "metal": {"Metallic": 1.0, "Roughness": 0.25},
    "dark": {"Roughness": 0.5, "Specular": 0.4},
    "bright": {"Roughness": 0.6, "Specular": 0.4},
}


def srgb_to_linear(c):
    c = np.asarray(c, float) / 255.0
    return np.where(c <= 0.04045, c / 12.92, ((c + 0.055) / 1.055) ** 2.4)


def srgb_encode(v):
    """Linear light (clipped to [0, 1]) to sRGB-encoded values in [0, 1]."""
    v = np.clip(v, 0.0, 1.0)
    return np.where(v <= 0.0031308, 12.92 * v, 1.055 * np.power(v, 1 / 2.4) - 0.055)


def apply_sensor(lin, sensor, rng):
    """The sensor model on scene-linear BGR: Gaussian lens blur (sensor["lens_blur_px"]), then
    Gaussian read noise plus shot noise, variance noise_sigma² + shot_noise_gain·value."""
    import cv2  # the Blender-side scripts import this module without OpenCV
    if sensor["lens_blur_px"] > 0:
        lin = cv2.GaussianBlur(lin, (0, 0), float(sensor["lens_blur_px"]),
                               borderType=cv2.BORDER_REFLECT)
    sigma = np.sqrt(sensor["noise_sigma"] ** 2 + sensor["shot_noise_gain"] * np.maximum(lin, 0))
    return lin + sigma * rng.standard_normal(lin.shape)


def copy_sequence_without_frames(src, dst):
    """Copies a pbr_synth.sh sequence's contract and gt/ from `src` to a new `dst`, without the
    camera folders of frames (and raw/); returns the camera names (those of gt/mask/)."""
    if os.path.exists(dst):
        raise SystemExit(f"{dst}: exists; remove it first")
    cameras = sorted(os.listdir(os.path.join(src, "gt", "mask")))
    shutil.copytree(src, dst, ignore=shutil.ignore_patterns(*cameras, "raw"))
    shutil.copytree(os.path.join(src, "gt"), os.path.join(dst, "gt"), dirs_exist_ok=True)
    for camera in cameras:
        os.makedirs(os.path.join(dst, camera))
    return cameras


def make_plan(spec):
    rng = np.random.default_rng(int(spec["seed"]))
    cam, obj, mot = spec["camera"], spec["object"], spec["motion"]
    n = int(spec["frames"])

    verts, tris = load_mesh_arrays(obj["mesh_path"])
    used = verts[np.unique(tris)]
    raw_min, raw_max = used.min(0), used.max(0)
    unit_to_mm = float(obj["size_mm"]) / float((raw_max - raw_min).max())
    bbox_center_mm = 0.5 * (raw_min + raw_max) * unit_to_mm

    # Rig: the target point above the table, two cameras on a circle about the vertical (and
    # any extra views on the same sphere).
    table_top_mm = 750.0
    target = np.array([0.0, 0.0, table_top_mm + float(mot["lift_mm"])])
    w, h = int(cam["width"]), int(cam["height"])
    fx = float(cam["f_px"])
    fy = fx * float(cam["fy_over_fx"])
    cx = (w - 1) / 2.0 + float(cam["principal_offset_px"][0])
    cy = (h - 1) / 2.0 + float(cam["principal_offset_px"][1])
    cameras = []
    half = 0.5 * float(cam["included_angle_deg"])
    views = [(cam["azimuth_deg"] - half, cam["elevation_deg"]),
             (cam["azimuth_deg"] + half, cam["elevation_deg"])]
    views += [(float(az), float(el)) for az, el in cam["extra_views"]]
    for i, (az, el) in enumerate(views):
        a, e = math.radians(az), math.radians(el)
        d = float(cam["distance_mm"])
        eye = target + d * np.array([math.cos(e) * math.cos(a), math.cos(e) * math.sin(a),
                                     math.sin(e)])
        world_from_cam = look_at_cv(eye, target)
        cameras.append({"name": f"cam{i}", "width": w, "height": h, "K": [fx, fy, cx, cy],
                        "world_from_cam": world_from_cam,
                        "cam_from_rig": np.linalg.inv(world_from_cam)})

    # Object motion: smooth random translation (two sinusoids per axis) and rotation (integrated
    # smooth angular velocity), the bbox centre following the translation.
    amp = np.asarray(mot["amplitude_mm"], float)
    t = np.arange(n, dtype=float)
    centre = np.tile(target, (n, 1))
    for axis in range(3):
        for period, share in ((n * rng.uniform(0.9, 1.4), 0.7), (n * rng.uniform(0.3, 0.5), 0.3)):
            centre[:, axis] += share * amp[axis] * np.sin(2 * math.pi * t / period +
                                                          rng.uniform(0, 2 * math.pi))
    rot_rate = math.radians(float(mot["rotation_deg_per_frame"]))
    axes = [unit_vector(rng) for _ in range(3)]
    periods = [n * rng.uniform(0.6, 1.5) for _ in range(3)]
    phases = [rng.uniform(0, 2 * math.pi) for _ in range(3)]
    r = exp_so3(unit_vector(rng) * rng.uniform(0, math.pi))
    world_from_object = []
    for k in range(n):
        if k > 0:
            omega = sum(axes[j] * math.sin(2 * math.pi * k / periods[j] + phases[j])
                        for j in range(3))
            omega = omega / max(np.linalg.norm(omega), 1e-9) * rot_rate * rng.uniform(0.6, 1.0)
            r = nearest_rotation(exp_so3(omega) @ r)
        world_from_object.append(iso(r, centre[k] - r @ bbox_center_mm))

    # init_pose.txt: frame 0 perturbed by exactly the configured magnitudes about the bbox centre.
    init_axis, init_dir = unit_vector(rng), unit_vector(rng)
    g0 = world_from_object[0]
    r0 = nearest_rotation(exp_so3(math.radians(spec["init"]["rotation_deg"]) * init_axis) @ g0[:3, :3])
    c0 = centre[0] + float(spec["init"]["translation_mm"]) * init_dir
    init_pose = iso(r0, c0 - r0 @ bbox_center_mm)

    # Lights.
    li = spec["lights"]
    key_az = np.full(n, float(li["key_azimuth_deg"]))
    if li["key_azimuth_end_deg"] is not None:
        key_az = np.linspace(float(li["key_azimuth_deg"]), float(li["key_azimuth_end_deg"]), n)
    points = []
    for _ in range(int(li["points"])):
        points.append([rng.uniform(-1.6, 1.6), rng.uniform(-1.6, 1.6), rng.uniform(1.2, 2.4)])

    # Clutter on the table (kept away from the object's column) and on the floor.
    clutter = []
    for i in range(int(spec["scene"]["clutter"])):
        on_table = i % 3 != 2
        while True:
            if on_table:
                p = np.array([rng.uniform(-550, 550), rng.uniform(-350, 350), table_top_mm])
            else:
                p = np.array([rng.uniform(-1700, 1700), rng.uniform(-1700, 1700), 0.0])
            if np.linalg.norm(p[:2] - target[:2]) > 230:
                break
        clutter.append({
            "shape": ["cube", "cylinder", "sphere", "cone", "torus"][int(rng.integers(0, 5))],
            "size_mm": float(rng.uniform(50, 130) if on_table else rng.uniform(150, 400)),
            "position_mm": p.tolist(),
            "yaw_deg": float(rng.uniform(0, 360)),
            "color_rgb": rng.integers(20, 235, size=3).tolist(),
            "material": ["diffuse", "plastic", "glossy", "dark", "bright"][int(rng.integers(0, 5))],
        })

    # Distractors: one per camera, the object's material and colour, placed every frame behind
    # the object along that camera's view so that their images touch (slightly overlap) the
    # object's image on a side that turns slowly.
    distractors = []
    if spec["scene"]["distractors"]:
        for ci, c in enumerate(cameras):
            shape = ["sphere", "cube", "cylinder"][int(rng.integers(0, 3))]
            size = float(obj["size_mm"]) * rng.uniform(0.5, 0.8)
            depth = rng.uniform(120, 250)
            angle0 = rng.uniform(0, 2 * math.pi)
            spin = rng.uniform(-0.6, 0.6) * 2 * math.pi / n
            cam_from_world = c["cam_from_rig"]
            positions = []
            for k in range(n):
                pc = cam_from_world[:3, :3] @ centre[k] + cam_from_world[:3, 3]
                r_obj = 0.5 * float(obj["size_mm"]) * 0.8 / pc[2]  # image radius / f
                zd = pc[2] + depth
                r_d = 0.5 * size / zd
                ang = angle0 + spin * k
                u = np.array([math.cos(ang), math.sin(ang)])
                offset = (r_obj + (1.0 - 2.0 * float(spec["scene"]["distractor_overlap"])) * r_d)
                xy = pc[:2] / pc[2] + offset * u
                p_cam = np.array([xy[0] * zd, xy[1] * zd, zd])
                positions.append((c["world_from_cam"][:3, :3] @ p_cam +
                                  c["world_from_cam"][:3, 3]).tolist())
            distractors.append({"shape": shape, "size_mm": size, "positions_mm": positions,
                                "yaw_deg": float(rng.uniform(0, 360))})

    occluder = None
    if spec["scene"]["occluder"]:
        # A finger-like capsule between cam0 (or, occluder_between_cameras, a viewpoint midway
        # between the first two cameras) and the object, sweeping across it.
        if spec["scene"]["occluder_between_cameras"]:
            a, e = math.radians(cam["azimuth_deg"]), math.radians(cam["elevation_deg"])
            eye = target + float(cam["distance_mm"]) * np.array(
                [math.cos(e) * math.cos(a), math.cos(e) * math.sin(a), math.sin(e)])
            world_from_view = look_at_cv(eye, target)
        else:
            world_from_view = cameras[0]["world_from_cam"]
        view_from_world = np.linalg.inv(world_from_view)
        positions = []
        for k in range(n):
            pc = view_from_world[:3, :3] @ centre[k] + view_from_world[:3, 3]
            s = -1.0 + 2.0 * k / max(n - 1, 1)
            p_view = pc + np.array([s * 80.0, float(spec["scene"]["occluder_drop_mm"]),
                                    -float(spec["scene"]["occluder_distance_mm"])])
            positions.append((world_from_view[:3, :3] @ p_view + world_from_view[:3, 3]).tolist())
        occluder = {"positions_mm": positions,
                    "radius_mm": float(spec["scene"]["occluder_radius_mm"]),
                    "length_mm": float(spec["scene"]["occluder_length_mm"]),
                    "color_rgb": [float(v) for v in spec["scene"]["occluder_color_rgb"]],
                    "material": spec["scene"]["occluder_material"]}

    return {
        "frames": n, "fps": float(spec["fps"]),
        "mesh": {"path": obj["mesh_path"], "unit_to_mm": unit_to_mm,
                 "bbox_center_mm": bbox_center_mm.tolist(),
                 "bbox_min_mm": (raw_min * unit_to_mm).tolist(),
                 "bbox_max_mm": (raw_max * unit_to_mm).tolist()},
        "cameras": [{**c, "world_from_cam": c["world_from_cam"].tolist(),
                     "cam_from_rig": c["cam_from_rig"].tolist()} for c in cameras],
        "world_from_object": [m.tolist() for m in world_from_object],
        "init_pose": init_pose.tolist(),
        "target_mm": target.tolist(), "table_top_mm": table_top_mm,
        "key_azimuth_deg": key_az.tolist(), "points_m": points,
        "clutter": clutter, "distractors": distractors, "occluder": occluder,
    }


def project_box(plan, cam_index, frame, points_mm, margin_px):
    """Integer pixel window [x0, x1) × [y0, y1) around the projections of `points_mm`
    (world frame), grown by margin_px and clipped to the image; None when behind the camera."""
    c = plan["cameras"][cam_index]
    cfr = np.asarray(c["cam_from_rig"])
    p = (cfr[:3, :3] @ np.asarray(points_mm, float).T).T + cfr[:3, 3]
    if (p[:, 2] <= 1.0).any():
        return None
    fx, fy, cx, cy = c["K"]
    u = fx * p[:, 0] / p[:, 2] + cx
    v = fy * p[:, 1] / p[:, 2] + cy
    x0 = max(0, int(math.floor(u.min() - margin_px)))
    y0 = max(0, int(math.floor(v.min() - margin_px)))
    x1 = min(c["width"], int(math.ceil(u.max() + margin_px)) + 1)
    y1 = min(c["height"], int(math.ceil(v.max() + margin_px)) + 1)
    if x1 <= x0 or y1 <= y0:
        return None
    return x0, y0, x1, y1


def object_corners_world(plan, frame):
    lo, hi = np.asarray(plan["mesh"]["bbox_min_mm"]), np.asarray(plan["mesh"]["bbox_max_mm"])
    corners = np.array([[x, y, z] for x in (lo[0], hi[0]) for y in (lo[1], hi[1])
                        for z in (lo[2], hi[2])])
    m = np.asarray(plan["world_from_object"][frame])
    return (m[:3, :3] @ corners.T).T + m[:3, 3]


def distractor_corners_world(plan, cam_index, frame):
    if cam_index >= len(plan["distractors"]):
        return np.zeros((0, 3))
    d = plan["distractors"][cam_index]
    r = 0.75 * d["size_mm"]  # bounds any primitive of that size, any orientation
    p = np.asarray(d["positions_mm"][frame])
    return np.array([p + np.array([x, y, z]) for x in (-r, r) for y in (-r, r) for z in (-r, r)])


# ---------------------------------------------------------------------------------------------
# Contract writers (formats of include/bcot/core/*_io.h)

def fmt_num(x):
    x = float(x)
    if x == 0.0:
        return "0"
    if x == int(x) and abs(x) < 1e15:
        return str(int(x))
    return repr(x)


def pose_line(m):
    m = np.asarray(m, float)
    vals = list(m[:3, :3].reshape(-1)) + list(m[:3, 3])
    return "\t".join(fmt_num(v) for v in vals)


def write_atomic(path, data):
    os.makedirs(os.path.dirname(path) or ".", exist_ok=True)
    tmp = path + ".tmp"
    mode = "wb" if isinstance(data, bytes) else "w"
    with open(tmp, mode) as f:
        f.write(data)
    os.replace(tmp, path)


def write_poses(path, poses):
    write_atomic(path, "".join(pose_line(p) + "\n" for p in poses))


def write_contract(plan, spec, out):
    """rig.yaml, object.yaml + model/, init_pose.txt, timestamps.csv and gt/ poses."""
    text = "cameras:\n"
    for c in plan["cameras"]:
        text += f"  - name: {c['name']}\n"
        text += f"    image_size: [{c['width']}, {c['height']}]\n"
        text += "    K: [" + ", ".join(fmt_num(v) for v in c["K"]) + "]\n"
        m = np.asarray(c["cam_from_rig"])
        rows = [", ".join(fmt_num(v) for v in m[r]) for r in range(4)]
        text += "    cam_from_rig: [" + ",\n                   ".join(rows) + "]\n"
    write_atomic(os.path.join(out, "rig.yaml"), text)

    mesh_path = plan["mesh"]["path"]
    stem, ext = os.path.splitext(os.path.basename(mesh_path))
    os.makedirs(os.path.join(out, "model"), exist_ok=True)
    shutil.copyfile(mesh_path, os.path.join(out, "model", stem + ext))
    write_atomic(os.path.join(out, "object.yaml"),
                 f"name: {stem}\nmesh: model/{stem}{ext}\nunit_to_mm: "
                 f"{fmt_num(plan['mesh']['unit_to_mm'])}\n")

    rig_from_object = [np.asarray(m) for m in plan["world_from_object"]]
    write_poses(os.path.join(out, "gt", "rig_from_object.txt"), rig_from_object)
    write_poses(os.path.join(out, "gt", "world_from_rig.txt"), [np.eye(4)] * len(rig_from_object))
    write_poses(os.path.join(out, "gt", "world_from_object.txt"), rig_from_object)
    for c in plan["cameras"]:
        cfr = np.asarray(c["cam_from_rig"])
        write_poses(os.path.join(out, "gt", c["name"], "pose.txt"),
                    [cfr @ m for m in rig_from_object])
    write_poses(os.path.join(out, "init_pose.txt"), [np.asarray(plan["init_pose"])])
    csv = "frame," + ",".join(c["name"] for c in plan["cameras"]) + "\n"
    for k in range(plan["frames"]):
        stamp = int(round(k * 1e9 / plan["fps"]))
        csv += f"{k}," + ",".join(str(stamp) for _ in plan["cameras"]) + "\n"
    write_atomic(os.path.join(out, "timestamps.csv"), csv)
    write_atomic(os.path.join(out, "pbr.resolved.json"), json.dumps(spec, indent=2) + "\n")
