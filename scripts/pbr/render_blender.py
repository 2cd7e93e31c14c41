"""Renders one physically based sequence with Blender Cycles (CPU, headless), issue 12.

Run by scripts/pbr_synth.sh, not directly:
  blender -b --factory-startup --python scripts/pbr/render_blender.py -- \
      --spec configs/pbr/bunny_plastic.json --raw OUT/raw [--set section.key=value ...]
Writes scene-linear, unclipped OpenEXR images OUT/raw/<camera>/NNNNNN.exr (the beauty pass,
before the sensor model of postprocess.py; by default RGBA with alpha 1 only in a window around
the object and its distractor, the rest coming from the low-resolution
OUT/raw/bg/<camera>/NNNNNN.exr), OUT/raw/mask/<camera>/NNNNNN.png (16-bit RGBA, alpha = coverage of
the annotated object alone: every other object hidden, box pixel filter of one pixel, no
motion blur or depth of field) and OUT/raw/plan.json, OUT/raw/timing.json.

Camera conversion: Blender's camera looks down −z with y up, so its world matrix is
world_from_cam(OpenCV) · diag(1, −1, −1). Blender's pixel i covers [i, i+1) (centre i + ½)
whereas bcot's pixel centre is at integer i, so the principal point in Blender's pixel
coordinates is (cx + ½, cy + ½); it is set through shift_x / shift_y (units of the image
width with sensor_fit HORIZONTAL; shift_y in fy-scaled units, hence the factor fx/fy), the
focal length through lens / sensor_width, fy/fx through the pixel aspect (pixel_aspect_x /
pixel_aspect_y = fy/fx). pbr_gt_check verified fy/fx = 0.95, 1 and 1.05 to ~0.01 px.
"""
import argparse
import json
import math
import os
import sys
import time

import bpy
import numpy as np
from mathutils import Matrix

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import pbr_common as pc  # noqa: E402

MM = 0.001  # Blender units are metres


def parse_args():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    ap = argparse.ArgumentParser()
    ap.add_argument("--spec", required=True)
    ap.add_argument("--raw", required=True)
    ap.add_argument("--set", action="append", default=[])
    ap.add_argument("--threads", type=int, default=int(os.environ.get("BCOT_PBR_THREADS", "2")))
    return ap.parse_args(argv)


def material(name, preset, color_rgb):
    m = bpy.data.materials.new(name)
    m.use_nodes = True
    bsdf = m.node_tree.nodes["Principled BSDF"]
    lin = pc.srgb_to_linear(color_rgb)
    if preset == "dark":
        lin = lin * 0.08
    elif preset == "bright":
        lin = np.clip(0.35 + 0.65 * lin, 0, 0.9)
    bsdf.inputs["Base Color"].default_value = (*lin.tolist(), 1.0)
    for key, value in pc.MATERIALS[preset].items():
        bsdf.inputs[key].default_value = value
    return m


def primitive(shape, size_m):
    r = 0.5 * size_m
    if shape == "cube":
        bpy.ops.mesh.primitive_cube_add(size=size_m)
    elif shape == "cylinder":
        bpy.ops.mesh.primitive_cylinder_add(radius=r, depth=size_m, vertices=48)
    elif shape == "sphere":
        bpy.ops.mesh.primitive_uv_sphere_add(radius=r, segments=48, ring_count=24)
    elif shape == "cone":
        bpy.ops.mesh.primitive_cone_add(radius1=r, depth=size_m, vertices=48)
    else:
        bpy.ops.mesh.primitive_torus_add(major_radius=0.7 * r, minor_radius=0.3 * r)
    ob = bpy.context.active_object
    bpy.ops.object.shade_smooth()
    return ob


def box(name, size_m, location_m, mat):
    bpy.ops.mesh.primitive_cube_add(size=1.0, location=location_m)
    ob = bpy.context.active_object
    ob.name = name
    ob.scale = size_m
    ob.data.materials.append(mat)
    return ob


def look_rotation(direction):
    """Rotation whose −z axis points along `direction` (lights, Blender convention)."""
    d = np.asarray(direction, float)
    d /= np.linalg.norm(d)
    z = -d
    x = np.cross([0.0, 0.0, 1.0], z)
    if np.linalg.norm(x) < 1e-6:
        x = np.array([1.0, 0.0, 0.0])
    x /= np.linalg.norm(x)
    y = np.cross(z, x)
    return Matrix(np.column_stack([x, y, z]).tolist()).to_quaternion()


def main():
    args = parse_args()
    spec = pc.load_spec(args.spec, args.set)
    plan = pc.make_plan(spec)
    os.makedirs(args.raw, exist_ok=True)
    n = plan["frames"]

    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    scene.frame_start, scene.frame_end = 0, n - 1
    r = scene.render
    rs = spec["render"]
    r.engine = "CYCLES"
    scene.cycles.device = "CPU"
    scene.cycles.samples = int(rs["samples"])
    scene.cycles.use_adaptive_sampling = rs["adaptive_threshold"] > 0
    scene.cycles.adaptive_threshold = float(rs["adaptive_threshold"] or 0.01)
    scene.cycles.use_denoising = False  # Debian's Blender has no OpenImageDenoise
    scene.cycles.max_bounces = int(rs["max_bounces"])
    scene.cycles.diffuse_bounces = min(2, int(rs["max_bounces"]))
    scene.cycles.glossy_bounces = min(1, int(rs["max_bounces"]))
    scene.cycles.transmission_bounces = 0
    scene.cycles.volume_bounces = 0
    scene.cycles.transparent_max_bounces = 2
    scene.cycles.caustics_reflective = False
    scene.cycles.caustics_refractive = False
    scene.cycles.sample_clamp_indirect = 10.0
    scene.cycles.seed = int(spec["seed"])
    scene.cycles.use_animated_seed = True
    r.threads_mode = "FIXED"
    r.threads = max(1, args.threads)
    r.use_persistent_data = True  # keep the BVH and shaders between the renders of a frame
    r.resolution_x = plan["cameras"][0]["width"]
    r.resolution_y = plan["cameras"][0]["height"]
    r.resolution_percentage = 100
    r.use_border = False
    # Beauty: scene-linear OpenEXR, unclipped; the sensor model (postprocess.py) blurs, adds
    # noise and only then clips, as a camera's optics come before its pixels saturate.
    r.image_settings.file_format = "OPEN_EXR"
    r.image_settings.color_mode = "RGB"
    r.image_settings.color_depth = "32"
    r.image_settings.exr_codec = "ZIP"
    scene.view_settings.view_transform = "Standard"
    scene.view_settings.look = "None"
    scene.view_settings.exposure = float(rs["exposure"])
    scene.display_settings.display_device = "sRGB"
    if rs["motion_blur_shutter"] > 0:
        r.use_motion_blur = True
        r.motion_blur_shutter = float(rs["motion_blur_shutter"])

    # World: a dim uniform sky.
    world = bpy.data.worlds.new("world")
    scene.world = world
    world.use_nodes = True
    bg = world.node_tree.nodes["Background"]
    bg.inputs["Color"].default_value = (0.8, 0.85, 1.0, 1.0)
    bg.inputs["Strength"].default_value = float(spec["lights"]["ambient"])

    # Room, table.
    sc = spec["scene"]
    table_top = plan["table_top_mm"] * MM
    if sc["room"]:
        floor = material("floor", "diffuse", [120, 110, 100])
        wall = material("wall", "diffuse", [185, 180, 170])
        box("floor", (5.0, 5.0, 0.02), (0, 0, -0.01), floor)
        box("wall_n", (5.0, 0.02, 2.8), (0, 2.5, 1.4), wall)
        box("wall_s", (5.0, 0.02, 2.8), (0, -2.5, 1.4), wall)
        box("wall_e", (0.02, 5.0, 2.8), (2.5, 0, 1.4), wall)
        box("wall_w", (0.02, 5.0, 2.8), (-2.5, 0, 1.4), wall)
    if sc["table"]:
        wood = material("table", "plastic", [140, 100, 70])
        box("table_top", (1.3, 0.9, 0.03), (0, 0, table_top - 0.015), wood)
        legs = material("legs", "metal", [150, 150, 155])
        for sx in (-0.6, 0.6):
            for sy in (-0.4, 0.4):
                box("leg", (0.04, 0.04, table_top - 0.03), (sx, sy, 0.5 * (table_top - 0.03)), legs)

    for i, c in enumerate(plan["clutter"]):
        ob = primitive(c["shape"], c["size_mm"] * MM)
        ob.name = f"clutter{i}"
        p = np.asarray(c["position_mm"]) * MM
        ob.location = (p[0], p[1], p[2] + 0.5 * c["size_mm"] * MM)
        ob.rotation_euler = (0, 0, math.radians(c["yaw_deg"]))
        ob.data.materials.append(material(f"clutter{i}", c["material"], c["color_rgb"]))

    # The annotated object: the mesh file's raw coordinates × unit_to_mm, in metres.
    verts, tris = pc.load_mesh_arrays(plan["mesh"]["path"])
    mesh = bpy.data.meshes.new("object")
    mesh.from_pydata((verts * plan["mesh"]["unit_to_mm"] * MM).tolist(), [], tris.tolist())
    mesh.update()
    for poly in mesh.polygons:
        poly.use_smooth = True
    smooth_angle_deg = float(spec["object"]["smooth_angle_deg"])  # (0, 180], load_spec checks
    if smooth_angle_deg < 180.0:
        mesh.use_auto_smooth = True  # edges sharper than the angle split the normals
        mesh.auto_smooth_angle = math.radians(smooth_angle_deg)
    obj = bpy.data.objects.new("object", mesh)
    scene.collection.objects.link(obj)
    obj_mat = material("object", spec["object"]["material"], spec["object"]["color_rgb"])
    mesh.materials.append(obj_mat)
    obj.rotation_mode = "QUATERNION"
    for k, m in enumerate(plan["world_from_object"]):
        m = np.asarray(m)
        mw = Matrix(m.tolist())
        mw.translation = (m[:3, 3] * MM).tolist()
        obj.matrix_world = mw
        obj.keyframe_insert("location", frame=k)
        obj.keyframe_insert("rotation_quaternion", frame=k)

    distractor_objs = []
    for i, d in enumerate(plan["distractors"]):
        ob = primitive(d["shape"], d["size_mm"] * MM)
        ob.name = f"distractor{i}"
        ob.data.materials.append(obj_mat)
        ob.rotation_euler = (0.3, 0.2, math.radians(d["yaw_deg"]))
        for k, p in enumerate(d["positions_mm"]):
            ob.location = (np.asarray(p) * MM).tolist()
            ob.keyframe_insert("location", frame=k)
        distractor_objs.append(ob)

    if plan["occluder"]:
        o = plan["occluder"]
        bpy.ops.mesh.primitive_cylinder_add(radius=o["radius_mm"] * MM, depth=o["length_mm"] * MM,
                                            vertices=32)
        ob = bpy.context.active_object
        bpy.ops.object.shade_smooth()
        ob.name = "occluder"
        ob.data.materials.append(material("occluder", o["material"], o["color_rgb"]))
        ob.rotation_euler = (0.4, 1.1, 0.0)
        for k, p in enumerate(o["positions_mm"]):
            ob.location = (np.asarray(p) * MM).tolist()
            ob.keyframe_insert("location", frame=k)

    # Lights: a soft key area light from above (possibly moving in azimuth), a weak fill from
    # the opposite side, low, and a few weak point lights.
    li = spec["lights"]
    target = np.asarray(plan["target_mm"]) * MM
    key_data = bpy.data.lights.new("key", "AREA")
    key_data.shape = "DISK"
    key_data.size = float(li["key_size_m"])
    key_data.energy = float(li["key_power_w"])
    key = bpy.data.objects.new("key", key_data)
    scene.collection.objects.link(key)
    key.rotation_mode = "QUATERNION"
    el = math.radians(li["key_elevation_deg"])
    for k, az_deg in enumerate(plan["key_azimuth_deg"]):
        az = math.radians(az_deg)
        direction = np.array([math.cos(el) * math.cos(az), math.cos(el) * math.sin(az), math.sin(el)])
        key.location = (target + float(li["key_distance_m"]) * direction).tolist()
        key.rotation_quaternion = look_rotation(-direction)
        key.keyframe_insert("location", frame=k)
        key.keyframe_insert("rotation_quaternion", frame=k)
    if li["fill_ratio"] > 0:
        fill_data = bpy.data.lights.new("fill", "AREA")
        fill_data.size = 1.0
        fill_data.energy = float(li["key_power_w"]) * float(li["fill_ratio"])
        fill = bpy.data.objects.new("fill", fill_data)
        scene.collection.objects.link(fill)
        az = math.radians(li["key_azimuth_deg"] + 180.0)
        direction = np.array([math.cos(az) * 0.95, math.sin(az) * 0.95, 0.3])
        fill.location = (target + 1.8 * direction).tolist()
        fill.rotation_mode = "QUATERNION"
        fill.rotation_quaternion = look_rotation(-direction)
    for i, p in enumerate(plan["points_m"]):
        pd = bpy.data.lights.new(f"point{i}", "POINT")
        pd.energy = float(li["point_power_w"])
        pd.shadow_soft_size = 0.05
        po = bpy.data.objects.new(f"point{i}", pd)
        po.location = p
        scene.collection.objects.link(po)

    # Cameras.
    cams = []
    flip = np.diag([1.0, -1.0, -1.0, 1.0])
    for c in plan["cameras"]:
        cd = bpy.data.cameras.new(c["name"])
        w, h = c["width"], c["height"]
        fx, fy, cx, cy = c["K"]
        cd.sensor_fit = "HORIZONTAL"
        cd.sensor_width = 36.0
        cd.lens = fx * cd.sensor_width / w
        cd.shift_x = (0.5 * w - (cx + 0.5)) / w
        cd.shift_y = ((cy + 0.5) - 0.5 * h) / w * fx / fy
        cd.clip_start = 0.01
        cd.clip_end = 50.0
        if rs["dof_fstop"] > 0:
            cd.dof.use_dof = True
            cd.dof.focus_distance = float(spec["camera"]["distance_mm"]) * MM
            cd.dof.aperture_fstop = float(rs["dof_fstop"])
        co = bpy.data.objects.new(c["name"], cd)
        scene.collection.objects.link(co)
        m = np.asarray(c["world_from_cam"]) @ flip
        mw = Matrix(m.tolist())
        mw.translation = (m[:3, 3] * MM).tolist()
        co.matrix_world = mw
        cams.append((c, co, fx, fy))
    # Pixel aspect (fy/fx): Blender scales x when pixel_aspect_x > pixel_aspect_y.
    fx0, fy0 = cams[0][2], cams[0][3]
    r.pixel_aspect_x, r.pixel_aspect_y = (fy0 / fx0, 1.0) if fy0 >= fx0 else (1.0, fx0 / fy0)

    with open(os.path.join(args.raw, "plan.json"), "w") as f:
        json.dump(plan, f)

    def set_border(window):
        if window is None:
            r.use_border = False
            return
        x0, y0, x1, y1 = window
        w, h = r.resolution_x, r.resolution_y
        r.use_border = True
        r.use_crop_to_border = False  # full-size RGBA, alpha 0 outside the window
        r.border_min_x, r.border_max_x = x0 / w, x1 / w
        r.border_min_y, r.border_max_y = (h - y1) / h, (h - y0) / h

    def render_to(out):
        part = out + ".part" + os.path.splitext(out)[1]  # Blender keeps the extension it sees
        r.filepath = part
        bpy.ops.render.render(write_still=True)
        os.replace(part, out)

    timing = {"beauty_s": [], "mask_s": []}
    roi_margin = float(rs["roi_margin_px"])
    for k in range(n):
        scene.frame_set(k)
        for ci, (c, co, _, _) in enumerate(cams):
            out = os.path.join(args.raw, c["name"], f"{k:06d}.exr")
            if os.path.exists(out):
                continue  # resume an interrupted render
            scene.camera = co
            t0 = time.time()
            if roi_margin >= 0:
                # Background: low resolution, few samples; then the window at full quality.
                r.resolution_percentage = int(round(100 / float(rs["background_scale"])))
                scene.cycles.samples = int(rs["background_samples"])
                set_border(None)
                r.image_settings.color_mode = "RGB"
                render_to(os.path.join(args.raw, "bg", c["name"], f"{k:06d}.exr"))
                r.resolution_percentage = 100
                scene.cycles.samples = int(rs["samples"])
                points = np.vstack([pc.object_corners_world(plan, k),
                                    pc.distractor_corners_world(plan, ci, k)])
                set_border(pc.project_box(plan, ci, k, points, roi_margin))
                r.image_settings.color_mode = "RGBA"
            render_to(out)
            timing["beauty_s"].append(time.time() - t0)
            print(f"pbr: frame {k} {c['name']} {timing['beauty_s'][-1]:.1f} s", flush=True)

    # Mask pass: the object alone, emission, transparent film (alpha = coverage), a box filter
    # one pixel wide (each sample uniform in the pixel's square), no blur of any kind.
    for ob in scene.objects:
        if ob.type == "MESH" and ob is not obj:
            ob.hide_render = True
    emit = bpy.data.materials.new("mask")
    emit.use_nodes = True
    nodes = emit.node_tree.nodes
    nodes.remove(nodes["Principled BSDF"])
    em = nodes.new("ShaderNodeEmission")
    emit.node_tree.links.new(em.outputs[0], nodes["Material Output"].inputs[0])
    mesh.materials[0] = emit
    bg.inputs["Strength"].default_value = 0.0
    r.film_transparent = True
    r.use_motion_blur = False
    scene.cycles.samples = int(rs["mask_samples"])
    scene.cycles.use_adaptive_sampling = False
    scene.cycles.max_bounces = 0
    scene.cycles.pixel_filter_type = "BOX"
    scene.cycles.filter_width = 1.0
    r.image_settings.file_format = "PNG"
    r.image_settings.color_depth = "16"
    r.image_settings.compression = 15
    r.image_settings.color_mode = "RGBA"
    for c, co, _, _ in cams:
        co.data.dof.use_dof = False
    r.resolution_percentage = 100
    for k in range(n):
        scene.frame_set(k)
        for ci, (c, co, _, _) in enumerate(cams):
            out = os.path.join(args.raw, "mask", c["name"], f"{k:06d}.png")
            if os.path.exists(out):
                continue
            scene.camera = co
            set_border(pc.project_box(plan, ci, k, pc.object_corners_world(plan, k), 4))
            t0 = time.time()
            render_to(out)
            timing["mask_s"].append(time.time() - t0)
    with open(os.path.join(args.raw, "timing.json"), "w") as f:
        json.dump(timing, f)


main()
