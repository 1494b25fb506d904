"""File > Import > CS488 Lua Scene: the script as Blender data, rendering the same pixels as
`python -m core render` (bpy 5.0 in this process, Debian's Blender 3.4 as `blender -b`).

The pixel comparisons check that the two front ends build the same scene; the accuracy of
what they render is checked against closed forms in tests/core/cs488/test_scenes.py."""

import math
import sys

import numpy as np
import pytest
from PIL import Image

import core
from core.cs488 import load_script
from core.image_io import to_bytes
from tests.blender.conftest import ROOT, clear_scene
from tests.core.cs488.test_scenes import SCENES
from tests.support.blender34 import blender_34

EVERY_COMMAND = SCENES / "every_command.lua"


def command_line_pixels(script, call_number=0, size=None):
    """What `python -m core render` writes for the script (tests/core/test_cli.py checks that
    the command line writes exactly these bytes)."""
    call = load_script(script, print_line=lambda line: None)[call_number]
    if size is not None:
        call.settings.width, call.settings.height = size
    return to_bytes(core.render(call.scene, call.settings).image)


def assert_same_picture(blender, expected):
    """The same bytes, but for a rare pixel one level off: Blender holds transforms in
    float32 and custom normals in 16 bits, which can tip a value across a rounding
    boundary (measured: none of 1,728 pixels in bpy 5.0, one in Blender 3.4)."""
    difference = np.abs(blender.astype(int) - expected.astype(int))
    assert difference.max() <= 1, difference.max()
    differing = np.count_nonzero(difference.max(axis=2))
    assert differing <= max(2, 0.001 * difference.shape[0] * difference.shape[1]), differing


@pytest.fixture
def imported(bpy_with_whitted):
    bpy = bpy_with_whitted
    clear_scene(bpy)

    def run(script):
        assert bpy.ops.import_scene.cs488_lua(filepath=str(script)) == {"FINISHED"}
        return bpy.context.scene

    return run


def render_png(bpy, scene, path):
    scene.render.filepath = str(path)
    bpy.ops.render.render(write_still=True, scene=scene.name)
    return np.asarray(Image.open(path))


def test_the_import_builds_blender_data_a_user_recognises(imported, bpy_with_whitted):
    bpy = bpy_with_whitted
    menu = bpy.types.TOPBAR_MT_file_import._dyn_ui_initialize()
    assert any(draw.__module__.endswith("lua.importer") for draw in menu)  # File > Import
    scene = imported(EVERY_COMMAND)
    objects = {obj.name: obj for obj in scene.objects}
    tags = {obj.whitted.shape for obj in objects.values() if obj.type == "MESH"}
    assert tags == {"SPHERE", "CUBE", "CYLINDER", "CONE", "TORUS", "MESH"}
    booleans = [m for obj in objects.values() for m in obj.modifiers if m.type == "BOOLEAN"]
    assert sorted(m.operation for m in booleans) == ["DIFFERENCE", "INTERSECT", "UNION"]
    assert all(m.object.hide_render and m.object.parent is obj for obj in objects.values()
               for m in obj.modifiers)  # fmt: skip
    assert objects["arm"].type == "EMPTY" and objects["sphere"].parent == objects["arm"]
    glass = objects["glass ball"].active_material.whitted
    assert glass.use_whitted and glass.transparency == 1.0
    assert math.isclose(glass.inner_ior, 1.53, rel_tol=1e-6)
    sphere_material = objects["sphere"].active_material
    assert sphere_material.whitted.image.colorspace_settings.name == "Non-Color"
    point, area = objects["Light 1"].data, objects["Light 2"].data
    assert (point.type, area.type, area.shape) == ("POINT", "AREA", "RECTANGLE")
    assert (area.size, area.size_y) == (4.0, 3.0)
    assert tuple(area.whitted.attenuation) == (1.0, 0.0, 0.0)
    camera = scene.camera.data
    assert math.isclose(math.degrees(camera.angle_y), 40.0, rel_tol=1e-6) and camera.dof.use_dof
    # The script's y is Blender's z, up: the camera as the scene's depsgraph places it
    placed = scene.camera.evaluated_get(scene.view_layers[0].depsgraph)
    assert placed.matrix_world.col[1][2] > 0.99
    assert tuple(scene.world.color) == pytest.approx((0.25, 0.25, 0.25))
    settings = scene.whitted
    assert (scene.render.resolution_x, scene.render.resolution_y) == (48, 36)
    assert (settings.max_depth, settings.pixel_samples, settings.shadow_samples) == (4, 3, 4)
    assert scene.view_settings.view_transform == "Raw"
    assert bpy.context.scene is scene


def test_blender_renders_the_same_pixels_as_the_command_line(imported, bpy_with_whitted, tmp_path):
    scene = imported(EVERY_COMMAND)
    blender = render_png(bpy_with_whitted, scene, tmp_path / "blender.png")
    assert_same_picture(blender, command_line_pixels(EVERY_COMMAND))


def test_each_render_call_is_a_scene_of_its_own(imported, bpy_with_whitted, tmp_path):
    """The report manual's script renders twice, the second time with depth of field."""
    imported(SCENES / "report_manual.lua")
    bpy = bpy_with_whitted
    focused = bpy.data.scenes["report_manual_dof"]
    assert focused.camera.data.dof.use_dof
    assert math.isclose(focused.camera.data.dof.focus_distance, 300.0)
    focused.render.resolution_x = focused.render.resolution_y = 64
    focused.whitted.shadow_samples = 4
    blender = render_png(bpy, focused, tmp_path / "dof.png")
    call = load_script(SCENES / "report_manual.lua", print_line=lambda line: None)[1]
    call.settings.width = call.settings.height = 64
    call.settings.shadow_samples = 4
    assert_same_picture(blender, to_bytes(core.render(call.scene, call.settings).image))


def test_a_bad_script_imports_nothing_and_names_its_line(imported, bpy_with_whitted, tmp_path):
    bpy = bpy_with_whitted
    script = tmp_path / "scene.lua"
    script.write_text("root = gr.node('root')\nroot:add_child(gr.sphere('a'))\ngr.cone('c', 2)\n")
    before = len(bpy.data.objects)
    with pytest.raises(RuntimeError, match=r"scene\.lua:3: gr\.cone: takes 1 argument"):
        bpy.ops.import_scene.cs488_lua(filepath=str(script))
    script.write_text("root = gr.node('root')\n")
    with pytest.raises(RuntimeError, match=r"scene\.lua: the script never calls gr\.render"):
        bpy.ops.import_scene.cs488_lua(filepath=str(script))
    assert len(bpy.data.objects) == before


def test_an_internal_failure_is_reported_not_raised(imported, bpy_with_whitted, tmp_path,
                                                    monkeypatch):  # fmt: skip
    """Whitted's own bug (here the build raises) reaches the user as the operator's error
    report, like a script's mistake, not as a traceback out of Blender's UI."""
    bpy = bpy_with_whitted
    lua_import = sys.modules["whitted.lua.importer"]  # the operator's module
    monkeypatch.setattr(lua_import, "import_script", lambda *args: 1 / 0)
    script = tmp_path / "scene.lua"
    script.write_text("root = gr.node('root')\n")
    with pytest.raises(RuntimeError, match=r"Whitted: the import failed: ZeroDivisionError"):
        bpy.ops.import_scene.cs488_lua(filepath=str(script))


@pytest.mark.blender34
def test_blender_34_imports_and_renders_the_same_pixels(tmp_path):
    run = blender_34(
        "--factory-startup", "--addons", "whitted", "--python-expr",
        "import bpy\n"
        "for o in list(bpy.data.objects): bpy.data.objects.remove(o)\n"
        f"bpy.ops.import_scene.cs488_lua(filepath={str(EVERY_COMMAND)!r})\n",
        "-o", f"{tmp_path}/out_####", "-F", "PNG", "-f", "1",
    )  # fmt: skip
    assert run.returncode == 0, run.stdout + run.stderr
    assert "Traceback" not in run.stdout + run.stderr
    blender = np.asarray(Image.open(tmp_path / "out_0001.png"))
    assert_same_picture(blender, command_line_pixels(EVERY_COMMAND))


def test_the_final_scene_script_imports_to_the_same_picture(imported, bpy_with_whitted, tmp_path):
    """Textures, a textured mesh floor, Newell's teapot with the report's vertex normals (in
    Blender as custom normals), CSG of a textured box, tori turned upright, a mirror."""
    script = ROOT / "sample_blends" / "final_scene.lua"
    scene = imported(script)
    scene.render.resolution_x = scene.render.resolution_y = 96
    scene.whitted.shadow_samples = 4
    blender = render_png(bpy_with_whitted, scene, tmp_path / "final.png")
    (call,) = load_script(script, print_line=lambda line: None)
    call.settings.width = call.settings.height = 96
    call.settings.shadow_samples = 4
    assert_same_picture(blender, to_bytes(core.render(call.scene, call.settings).image))


def scene_state(scene) -> dict:
    """What a user set up in a scene and would not want an import to change."""
    view = scene.view_settings
    return {
        "objects": sorted(obj.name for obj in scene.objects),
        "camera": scene.camera.name if scene.camera else None,
        "world": scene.world.name if scene.world else None,
        "colour": (view.view_transform, view.look, view.exposure, view.gamma),
        "render": (scene.render.engine, scene.render.resolution_x, scene.render.resolution_y,
                   scene.render.resolution_percentage, scene.render.filepath),
        "whitted": (scene.whitted.max_depth, scene.whitted.pixel_samples),
    }  # fmt: skip


def test_the_import_leaves_the_users_scene_as_it_was(sample_scene, bpy_with_whitted):
    """A new scene for the script, shown in the window; the open scene unchanged, down to
    its colour management (the script's scene renders with Raw)."""
    bpy = bpy_with_whitted
    before = scene_state(sample_scene)
    assert bpy.ops.import_scene.cs488_lua(filepath=str(EVERY_COMMAND)) == {"FINISHED"}
    assert scene_state(sample_scene) == before
    imported = bpy.context.scene
    assert imported is not sample_scene and imported.name.startswith("every_command")
    assert imported.view_settings.view_transform == "Raw" and imported.camera is not None
    assert not set(before["objects"]) & {obj.name for obj in imported.objects}


def test_into_the_current_scene_adds_objects_and_changes_no_setting(sample_scene, bpy_with_whitted):
    bpy = bpy_with_whitted
    before = scene_state(sample_scene)
    done = bpy.ops.import_scene.cs488_lua(filepath=str(EVERY_COMMAND), into="CURRENT_SCENE")
    assert done == {"FINISHED"} and bpy.context.scene is sample_scene
    after = scene_state(sample_scene)
    added = set(after.pop("objects")) - set(before.pop("objects"))
    assert after == before  # the camera, World, colour and render settings as they were
    assert any(name.startswith("Camera") for name in added) and len(added) > 5


@pytest.mark.parametrize("photons, automatic, count", [(", photons = 5000", False, 5000),
                                                       ("", True, None)])  # fmt: skip
def test_a_scripts_photon_budget_reaches_the_caustics_panel(
    imported, bpy_with_whitted, tmp_path, photons, automatic, count
):
    """gr.render's {photons = N} as Light Paths > Caustics > Photons with Automatic off; no
    count (or 'auto') leaves Automatic on, as the command line renders it."""
    from tests.core.cs488.test_render_options import MIRROR_SCENE, _render_line

    script = tmp_path / "mirror.lua"
    script.write_text(MIRROR_SCENE + _render_line(f", {{caustics = 'both'{photons}}}"))
    settings = imported(script).whitted
    assert settings.use_caustics_reflective and settings.use_auto_photons == automatic
    if count is not None:
        assert settings.caustic_photons == count
