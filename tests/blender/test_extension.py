"""The installable zip: Blender 5.0 installs it as an extension, and it renders at once with
the kernels it ships compiled."""

import os
import subprocess
import sys
import zipfile
from pathlib import Path

import pytest

from blender_addon.packaging.build_extension import build
from core.jit import CPU_TARGET

pytestmark = pytest.mark.bpy5

INSTALL_AND_RENDER = """
import sys, bpy
zip_path, out = sys.argv[1], sys.argv[2]
result = bpy.ops.extensions.package_install_files(
    filepath=zip_path, repo="user_default", enable_on_install=True)
assert result == {"FINISHED"}, result
for obj in list(bpy.data.objects):
    bpy.data.objects.remove(obj)
scene = bpy.context.scene
scene.render.engine = "WHITTED"
scene.render.resolution_x = scene.render.resolution_y = 16
bpy.ops.object.camera_add(location=(0, -6, 0), rotation=(1.5707963, 0, 0))
scene.camera = bpy.context.active_object
bpy.ops.whitted.add_shape(shape="SPHERE")
bpy.ops.object.light_add(type="POINT", location=(0, -4, 3))
bpy.context.active_object.data.energy = 2000
scene.render.filepath = out
bpy.ops.render.render(write_still=True)
print("ENGINE", [c.__module__ for c in bpy.types.RenderEngine.__subclasses__()])
result = bpy.ops.import_scene.cs488_lua(filepath=sys.argv[3])
print("IMPORTED", result, sorted(o.name for o in bpy.context.scene.objects))
"""


def test_the_zip_installs_as_an_extension_and_renders(tmp_path):
    # For this CPU's level only, in the shared test cache: loads, when other tests compiled
    # there first
    shared = Path(os.environ["WHITTED_CACHE_DIR"])
    target = build(tmp_path / "dist", False, kernel_cache=shared, levels=(CPU_TARGET,))
    with zipfile.ZipFile(target) as archive:
        names = archive.namelist()
        manifest = archive.read("blender_manifest.toml").decode()
    assert {"__init__.py", "engine.py", "lua_import.py", "core/__init__.py",
            "core/kernels/trace.py", "core/cs488/sandbox.py"} <= set(names)  # fmt: skip
    assert 'id = "whitted"' in manifest and 'type = "add-on"' in manifest
    # a new user: no kernel cache of their own yet
    env = dict(os.environ, BLENDER_USER_RESOURCES=str(tmp_path / "blender_home"))
    env["WHITTED_CACHE_DIR"] = str(tmp_path / "new_user_cache")
    # and another package named `core` ahead on the path, which the add-on must not import
    (tmp_path / "elsewhere" / "core").mkdir(parents=True)
    (tmp_path / "elsewhere" / "core" / "__init__.py").write_text("raise ImportError('foreign')")
    env["PYTHONPATH"] = str(tmp_path / "elsewhere")
    out = tmp_path / "sphere.png"
    script = tmp_path / "ball.lua"
    script.write_text(
        "root = gr.node('root')\nroot:add_child(gr.sphere('ball'))\n"
        "gr.render(root, 'ball.png', 8, 8, {0, 0, 5}, {0, 0, -1}, {0, 1, 0}, 50, {1, 1, 1}, {})\n"
    )
    run = subprocess.run(
        [sys.executable, "-c", INSTALL_AND_RENDER, str(target), str(out), str(script)],
        env=env, cwd=tmp_path, capture_output=True, text=True, timeout=600,
    )  # fmt: skip
    assert run.returncode == 0, run.stdout + run.stderr
    assert "bl_ext.user_default.whitted.engine" in run.stdout
    assert "copied the extension's compiled kernels" in run.stderr, run.stdout + run.stderr
    assert "Whitted: compiling kernels" not in run.stdout + run.stderr
    assert "IMPORTED {'FINISHED'}" in run.stdout and "'ball'" in run.stdout
    from PIL import Image

    image = Image.open(out).convert("RGB")
    centre, corner = image.getpixel((8, 8)), image.getpixel((0, 0))
    assert sum(centre) > sum(corner) + 60  # the lit sphere in front of the dark world
