"""The installable zip: each Blender 4.2+ installs it as an extension, beside another add-on
that brings a package named `core` of its own, in either order, and it renders at once with
the kernels it ships compiled, keeping them in the extension's own user folder."""

import os
import subprocess
import sys
import zipfile
from pathlib import Path

import numpy as np
import pytest
from PIL import Image

from blender_addon.packaging.build_extension import build
from core.jit.decorators import CPU_TARGET
from tests.blender.conftest import ROOT, SAMPLE

pytestmark = pytest.mark.bpy

# A legacy add-on the common way: its folder on sys.path, its own `core` imported top-level
OTHER_ADDON = """
import os, sys
sys.path.append(os.path.dirname(__file__))
import core
bl_info = {"name": "Other tool", "blender": (3, 4, 0), "category": "Object"}
def register():
    assert core.WHO == "the other add-on", core
def unregister():
    pass
"""

INSTALL_AND_RENDER = """
import sys, bpy
import addon_utils  # bpy as a module: importable once bpy is
zip_path, out, script, order, sample = sys.argv[1:6]
def enable_other():
    assert addon_utils.enable("other_tool", default_set=True, handle_error=None)
def install_whitted():
    result = bpy.ops.extensions.package_install_files(
        filepath=zip_path, repo="user_default", enable_on_install=True)
    assert result == {"FINISHED"}, result
if order == "other first":
    enable_other()
    install_whitted()
else:
    install_whitted()
    assert "core" not in sys.modules, sys.modules["core"]  # Whitted adds no top-level core
    enable_other()
import core
assert core.WHO == "the other add-on", core
assert "bl_ext.user_default.whitted.core" in sys.modules
bpy.ops.wm.open_mainfile(filepath=sample)
scene = bpy.context.scene
assert scene.render.engine == "WHITTED"
scene.render.resolution_percentage = PERCENT
scene.render.filepath = out
bpy.ops.render.render(write_still=True)
# The kernels load with the first render (core imports its driver on first use)
assert "bl_ext.user_default.whitted.core.kernels.trace" in sys.modules
assert bpy.ops.whitted.add_shape(shape="SPHERE") == {"FINISHED"}
print("ENGINE", [c.__module__ for c in bpy.types.RenderEngine.__subclasses__()])
result = bpy.ops.import_scene.cs488_lua(filepath=script)
print("IMPORTED", result, sorted(o.name for o in bpy.context.scene.objects))
assert sys.modules["core"].WHO == "the other add-on"
""".replace("PERCENT", "25")


@pytest.fixture(scope="module")
def extension_zip(tmp_path_factory):
    """The Linux zip as `make addon` builds it, wheels and all, but with kernels for this
    CPU's level and this Python only, compiled in the shared test cache (a second run only
    loads them); the wheels are downloaded once into .cache/wheels."""
    shared = Path(os.environ["WHITTED_CACHE_DIR"])
    out = tmp_path_factory.mktemp("dist")
    zips = build(
        out, kernel_cache=shared, levels=(CPU_TARGET,), platforms=("linux-x64",),
        wheel_cache=ROOT / ".cache" / "wheels",
    )  # fmt: skip
    return zips["linux-x64"]


@pytest.fixture(scope="module")
def checkout_render(bpy_with_whitted, tmp_path_factory):
    """The sample rendered in this process by the add-on a checkout links to."""
    bpy = bpy_with_whitted
    bpy.ops.wm.open_mainfile(filepath=str(SAMPLE))
    bpy.context.scene.render.resolution_percentage = 25
    out = tmp_path_factory.mktemp("checkout") / "sample.png"
    bpy.context.scene.render.filepath = str(out)
    bpy.ops.render.render(write_still=True)
    return out


def test_the_zip_holds_the_add_on_its_core_and_its_kernels(extension_zip):
    with zipfile.ZipFile(extension_zip) as archive:
        names = archive.namelist()
        manifest = archive.read("blender_manifest.toml").decode()
    assert {"__init__.py", "engine/final.py", "lua/importer.py", "core/__init__.py",
            "core/kernels/trace.py", "core/cs488/sandbox.py"} <= set(names)  # fmt: skip
    wheels = {n for n in names if n.startswith("wheels/")}
    assert len(wheels) == 8 and all(f'"./{w}"' in manifest for w in wheels), manifest
    assert any(n.startswith("kernel_cache/") and n.endswith(f"warm-{CPU_TARGET}.ok") for n in names)
    assert 'id = "whitted"' in manifest and 'type = "add-on"' in manifest


@pytest.mark.parametrize("order", ["other first", "whitted first"])
def test_installed_beside_another_core_it_renders_from_its_shipped_kernels(
    extension_zip, checkout_render, tmp_path, order
):
    # A new user: a Blender home and add-ons folder of their own, no kernel cache yet
    home = tmp_path / "blender_home"
    env = {k: v for k, v in os.environ.items() if k not in ("WHITTED_CACHE_DIR", "PYTHONPATH")}
    env.update(BLENDER_USER_RESOURCES=str(home), BLENDER_USER_SCRIPTS=str(tmp_path / "scripts"))
    other = tmp_path / "scripts" / "addons" / "other_tool"
    (other / "core").mkdir(parents=True)
    (other / "__init__.py").write_text(OTHER_ADDON)
    (other / "core" / "__init__.py").write_text('WHO = "the other add-on"\n')
    out = tmp_path / "sphere.png"
    script = tmp_path / "ball.lua"
    script.write_text(
        "root = gr.node('root')\nroot:add_child(gr.sphere('ball'))\n"
        "gr.render(root, 'ball.png', 8, 8, {0, 0, 5}, {0, 0, -1}, {0, 1, 0}, 50, {1, 1, 1}, {})\n"
    )
    command = [sys.executable, "-c", INSTALL_AND_RENDER, str(extension_zip), str(out)]
    run = subprocess.run(
        [*command, str(script), order, str(SAMPLE)],
        env=env, cwd=tmp_path, capture_output=True, text=True, timeout=600,
    )  # fmt: skip
    assert run.returncode == 0, run.stdout + run.stderr
    assert "bl_ext.user_default.whitted.engine" in run.stdout
    assert "copied the extension's compiled kernels" in run.stderr, run.stdout + run.stderr
    assert "Whitted: compiling kernels" not in run.stdout + run.stderr
    # and the render itself loaded them, compiling nothing (its stats say which)
    assert "kernels loaded from the cache" in run.stdout, run.stdout
    assert "first-use kernel compile" not in run.stdout, run.stdout
    assert "IMPORTED {'FINISHED'}" in run.stdout and "'ball'" in run.stdout
    # The kernels went where Blender keeps the extension's user data, not a shared folder
    kept = list(home.glob("extensions/.user/user_default/whitted/kernel_cache/whitted-*/warm-*"))
    assert kept, sorted(str(p.relative_to(home)) for p in home.rglob("*") if p.is_dir())[:20]
    # The same picture as the checkout's add-on makes in this Blender
    installed, checkout = (
        np.asarray(Image.open(p).convert("RGBA")) for p in (out, checkout_render)
    )
    assert installed.shape == checkout.shape and installed.std() > 10
    assert np.array_equal(installed, checkout)
