"""Writes a Catmull-Clark subdivision of a mesh, for a smooth-surface variant of a Cycles scene.

Usage: blender -b --factory-startup --python tests/bench/subdivide_mesh.py -- IN.obj OUT.obj LEVELS
The result is triangulated and keeps the input's axes. `scripts/pbr_synth.sh` renders it when a
scene spec's `object.mesh` names it (docs/notes/issue12_rim_shading.md, "a dense mesh").
Not a test.
"""
import sys

import bpy

args = sys.argv[sys.argv.index("--") + 1:]
if len(args) != 3:
    sys.exit(__doc__)
source, target, levels = args[0], args[1], int(args[2])
bpy.ops.wm.read_factory_settings(use_empty=True)
bpy.ops.import_scene.obj(filepath=source, axis_forward="-Z", axis_up="Y")
mesh = bpy.context.selected_objects[0]
bpy.context.view_layer.objects.active = mesh
modifier = mesh.modifiers.new("subdivision", "SUBSURF")
modifier.levels = levels
modifier.render_levels = levels
bpy.ops.object.modifier_apply(modifier=modifier.name)
bpy.ops.export_scene.obj(filepath=target, use_selection=True, use_materials=False,
                         use_normals=False, use_uvs=False, use_triangles=True,
                         axis_forward="-Z", axis_up="Y")
