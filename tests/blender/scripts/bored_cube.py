"""Run inside Blender: build a scene with a smooth mesh sphere, a tagged cube bored through by
a hidden tagged cylinder (a Boolean modifier) and both kinds of light, then render it with
Whitted to the path given after `--`."""

import math
import sys

import bpy

for obj in list(bpy.data.objects):
    bpy.data.objects.remove(obj)
scene = bpy.context.scene
scene.render.engine = "WHITTED"
scene.render.resolution_x, scene.render.resolution_y = 80, 60
scene.render.resolution_percentage = 100
# Looking along +y straight down the bore
bpy.ops.object.camera_add(location=(1.5, -8, 0), rotation=(math.pi / 2, 0, 0))
scene.camera = bpy.context.active_object
bpy.ops.mesh.primitive_uv_sphere_add(location=(-1.5, 0, 0))
bpy.ops.object.shade_smooth()
bpy.ops.mesh.primitive_cylinder_add(location=(1.5, 0, 0), rotation=(math.pi / 2, 0, 0))
cutter = bpy.context.active_object
cutter.scale = (0.4, 0.4, 2)
cutter.hide_render = True
cutter.whitted.shape = "CYLINDER"
bpy.ops.mesh.primitive_cube_add(location=(1.5, 0, 0))
cube = bpy.context.active_object
cube.whitted.shape = "CUBE"
bore = cube.modifiers.new("Bore", "BOOLEAN")
bore.operation = "DIFFERENCE"
bore.object = cutter
bpy.ops.object.light_add(type="AREA", location=(0, -3, 5))
bpy.context.active_object.data.energy = 2000
bpy.ops.object.light_add(type="POINT", location=(2, -4, 4))
bpy.context.active_object.data.energy = 2000
scene.render.filepath = sys.argv[sys.argv.index("--") + 1]
bpy.ops.render.render(write_still=True)
