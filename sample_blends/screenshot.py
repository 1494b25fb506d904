"""Take the README's screenshot from Blender's real window (run under Xvfb):

    xvfb-run -s "-screen 0 1600x900x24" blender --python sample_blends/screenshot.py -- OUT.png

Builds the bored-cube scene of the Blender tests, shows the Whitted Shape panel of the cube
(a CSG through its Boolean modifier), renders with F12's operator and grabs the screen with
ImageMagick's `import` once the render is in."""

import subprocess
import sys
from pathlib import Path

import bpy

OUT = sys.argv[sys.argv.index("--") + 1]
scene_script = Path(__file__).resolve().parent.parent / "tests/blender/scripts/bored_cube.py"
# Build the scene without rendering it: the script renders at its end, so run all but that
source = scene_script.read_text().split("scene.render.filepath")[0]
exec(compile(source, str(scene_script), "exec"), {"__name__": "scene"})
scene = bpy.context.scene
scene.render.resolution_x, scene.render.resolution_y = 480, 360
cube = scene.objects["Cube"]
for obj in scene.objects:
    obj.select_set(obj is cube)
bpy.context.view_layer.objects.active = cube
cube.data.materials.append(bpy.data.materials.new("Clay"))
for area in bpy.context.screen.areas:
    if area.type == "PROPERTIES":
        area.spaces[0].context = "OBJECT"
# Only for the picture: Blender's own object panels above ours would push it out of view
for name in ("OBJECT_PT_transform", "OBJECT_PT_delta_transform", "OBJECT_PT_relations"):
    panel = getattr(bpy.types, name, None)
    if panel is not None:
        bpy.utils.unregister_class(panel)


def grab():
    subprocess.run(["import", "-window", "root", OUT], check=True)
    bpy.ops.wm.quit_blender()


def render():
    bpy.ops.render.render("INVOKE_DEFAULT")
    bpy.app.timers.register(grab, first_interval=8.0)


bpy.app.timers.register(render, first_interval=3.0)
