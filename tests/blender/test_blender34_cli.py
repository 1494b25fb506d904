"""Debian's Blender 3.4 as a farm runs it: `blender -b scene.blend -E WHITTED -f 1`."""

import os
import re
import shutil
import subprocess

import numpy as np
import pytest
from PIL import Image

from tests.blender.conftest import ROOT, SAMPLE
from tests.support.blender34 import blender_34
from tests.support.blender_reference import expected_pixels, sample_grid
from tests.support.exr import read_exr

pytestmark = pytest.mark.blender34


def render_sample(output: str, file_format: str = "PNG", *before: str):
    """`blender -b` rendering the sample's frame 1 to `output` (a path with ####), after
    the arguments `before` (a --python-expr changing the scene)."""
    return blender_34(str(SAMPLE), "--addons", "whitted", "-E", "WHITTED", *before, "-o",
                      output, "-F", file_format, "-f", "1")  # fmt: skip


# The red sphere's material (the Whitted Material panel's) made a constant node graph the
# compile folds into the table (two Diffuse BSDFs mixed half and half), as a user's node
# materials mostly are
FOLDED_RED = (
    "import bpy; red = bpy.data.materials['Red']; red.whitted.use_whitted = False; "
    "tree = red.node_tree; "
    "a, b = tree.nodes.new('ShaderNodeBsdfDiffuse'), tree.nodes.new('ShaderNodeBsdfDiffuse'); "
    "a.inputs['Color'].default_value = (0.8, 0.1, 0.1, 1.0); "
    "mix = tree.nodes.new('ShaderNodeMixShader'); "
    "tree.links.new(a.outputs[0], mix.inputs[1]); tree.links.new(b.outputs[0], mix.inputs[2]); "
    "tree.links.new(mix.outputs[0], tree.nodes['Material Output'].inputs['Surface'])"
)


def test_a_first_render_on_a_new_machine_compiles_only_its_variant_and_says_each_step(
    tmp_path, monkeypatch
):
    """Without WHITTED_FULL_KERNEL (the suite sets it), `blender -b` from an empty cache waits
    for the warm-up process, printing each step as it starts, and warms the render kernel
    without the features the scene cannot use (core.jit.variants): the sample's spheres
    under the report's lights need none, so no photon step. Then it loads every kernel from
    the cache the warm-up filled, and the frame is the full kernel's to the bit (the shared
    cache's: the signature test's warm-up, which the add-on loads under its own name)."""
    shared = os.environ["WHITTED_CACHE_DIR"]
    monkeypatch.setenv("WHITTED_FULL_KERNEL", "0")
    monkeypatch.setenv("WHITTED_CACHE_DIR", str(tmp_path / "cache"))
    run = render_sample(f"{tmp_path}/variant_####", "OPEN_EXR", "--python-expr", FOLDED_RED)
    assert run.returncode == 0, run.stdout + run.stderr
    steps = [line for line in run.stdout.splitlines()
             if line.startswith("Whitted: compiling kernels: ") and " of " in line]  # fmt: skip
    # the packing's kernels compile beside the rest (core.jit.warmup.Beside)
    assert steps and steps[0] == "Whitted: compiling kernels: 1 of 4 (nearest hits)", run.stdout
    assert all(" of 4 (" in step for step in steps), run.stdout
    # the last step (waiting for what compiled beside) may pass before the render looks
    ready = re.search(r"^Whitted: kernels ready in [\d.]+ s \((.*)\)$", run.stdout, re.M)
    assert ready and ready.group(1).endswith(" s"), run.stdout
    assert "render kernel" in ready.group(1) and "scene packing " in ready.group(1), run.stdout
    assert "caustic" not in ready.group(1), run.stdout  # no photon kernels
    assert "exited with status" not in run.stdout
    markers = sorted((tmp_path / "cache").rglob("warm-*.ok"))
    assert len(markers) == 1 and "-without-" in markers[0].name, markers
    # Nothing compiled after the warm-up said the kernels were ready: the render ran only
    # its kernels, the fold of constant node materials (FOLDED_RED) among them, which the
    # variant without node programs needs too
    ready_at = markers[0].stat().st_mtime
    late = [p.name for p in (tmp_path / "cache").rglob("*.nbi") if p.stat().st_mtime > ready_at]
    assert not late, late
    # The render waited for the warm-up, said so apart from its own time, then loaded them
    assert "first-use kernel compile" in run.stdout, run.stdout[-2000:]
    assert "then loaded from the cache" in run.stdout, run.stdout[-2000:]
    monkeypatch.setenv("WHITTED_FULL_KERNEL", "1")
    monkeypatch.setenv("WHITTED_CACHE_DIR", shared)  # with the full kernel
    full = render_sample(f"{tmp_path}/full_####", "OPEN_EXR", "--python-expr", FOLDED_RED)
    assert full.returncode == 0, full.stdout + full.stderr
    variant, kept = read_exr(tmp_path / "variant_0001.exr")
    whole, _ = read_exr(tmp_path / "full_0001.exr")
    # The frame's metadata says the render time apart from the compile it waited for
    compiled = re.match(r"first-use kernel compile (\d+) s", kept.get("Whitted Kernels", ""))
    assert compiled, kept
    render_s = float(kept["Whitted Render Time"].removesuffix(" s"))
    assert render_s < 0.2 * int(compiled.group(1)), kept
    assert kept["Whitted"].startswith(f"{render_s:.2f} s |"), kept
    assert variant.keys() == whole.keys() and max(c.max() for c in variant.values()) > 0.1
    for name, channel in whole.items():
        np.testing.assert_array_equal(variant[name], channel, err_msg=name)


def test_headless_command_renders_the_sample(sample_scene, tmp_path):
    run = render_sample(f"{tmp_path}/out_####")
    assert run.returncode == 0, run.stdout + run.stderr
    assert "Blender 3.4" in run.stdout
    assert "Traceback" not in run.stdout + run.stderr
    image = np.asarray(Image.open(tmp_path / "out_0001.png"), dtype=float)
    assert image.shape == (240, 320, 4)
    sample_scene.render.resolution_percentage = 100
    pixels = sample_grid(320, 240, 11)
    expected = expected_pixels(sample_scene, pixels)
    got = np.array([image[py, px, :3] for px, py in pixels])
    np.testing.assert_allclose(got, expected, atol=1.6)


def test_meshes_tagged_shapes_booleans_and_area_lights_render_in_blender_34(tmp_path):
    script = ROOT / "tests" / "blender" / "scripts" / "bored_cube.py"
    out = tmp_path / "bored.png"
    run = blender_34("--addons", "whitted", "--python", str(script), "--", str(out))
    assert run.returncode == 0 and "Traceback" not in run.stdout + run.stderr, run.stdout
    assert "Error" not in run.stdout, run.stdout
    image = np.asarray(Image.open(out), dtype=float)[..., :3]
    background = image[2, 2]
    # Straight down the bore: the background; the cube's face beside it: lit
    np.testing.assert_allclose(image[30, 40], background, atol=1.0)
    assert image[30, 52].mean() > background.mean() + 20
    # The smooth mesh sphere, left of the cube
    assert image[30, 12].mean() > background.mean() + 20


def test_the_in_process_blender_tests_pass_inside_blender_34_too():
    """The export, engine, CSG-silhouette and sample-scene tests, written against the bpy 5.0
    module, run by pytest inside Debian's Blender 3.4: every version difference is covered,
    and every sample file opens in both."""
    files = [
        "test_export.py", "test_bpy_engine.py", "test_csg_silhouettes.py",
        "test_sample_scenes.py", "test_passes.py", "test_cycles_lights.py",
        "test_cycles_world.py", "test_cycles_materials.py", "test_cycles_textures.py",
        "test_cycles_glass_shadows.py", "test_caustics_in_blender.py", "test_cycles_facing.py",
        "test_cycles_value_nodes.py", "test_cycles_colour_attributes.py",
        "test_cycles_absorption.py", "test_cycles_translucent.py", "test_cycles_light_path.py",
        "test_cycles_geometry_node.py", "test_cycles_tangents.py",
        "test_cycles_rough_diffuse.py",
    ]  # fmt: skip
    paths = [str(ROOT / "tests" / "blender" / name) for name in files]
    code = (
        "import os, sys, pytest; "
        f"code = pytest.main(['-q', '-p', 'no:cacheprovider', *{paths!r}]); "
        "sys.stdout.flush(); os._exit(int(code))"
    )
    run = blender_34("--addons", "whitted", "--python-expr", code, timeout=900)
    assert run.returncode == 0, run.stdout[-4000:] + run.stderr[-2000:]
    assert "Blender 3.4" in run.stdout and " passed" in run.stdout


def test_a_farm_render_writes_every_pass_to_a_multilayer_exr(tmp_path):
    """`blender -b ... -F OPEN_EXR_MULTILAYER`: Combined, every pass the view layer asks for
    and the Cryptomatte manifests in one file (read back by tests/support/exr)."""
    switches = ("use_pass_z", "use_pass_mist", "use_pass_normal", "use_pass_position",
                "use_pass_uv", "use_pass_object_index", "use_pass_material_index",
                "use_pass_diffuse_color", "use_pass_shadow", "use_pass_environment",
                "use_pass_cryptomatte_object", "use_pass_cryptomatte_material")  # fmt: skip
    enable = (
        "import bpy; layer = bpy.context.scene.view_layers[0]; "
        f"[setattr(layer, name, True) for name in {switches!r}]; "
        "layer.whitted.use_pass_terms = True"
    )
    run = blender_34(
        str(SAMPLE), "--addons", "whitted", "-E", "WHITTED", "--python-expr", enable,
        "-o", f"{tmp_path}/out_####", "-F", "OPEN_EXR_MULTILAYER", "-f", "1",
    )  # fmt: skip
    assert run.returncode == 0 and "Traceback" not in run.stdout + run.stderr, run.stdout
    channels, metadata = read_exr(tmp_path / "out_0001.exr")
    passes = {name.split(".")[1] for name in channels}
    assert passes == {
        "Combined", "Depth", "Mist", "Normal", "Position", "UV", "IndexOB", "IndexMA",
        "DiffCol", "Shadow", "Env", "Whitted Ambient", "Whitted Diffuse", "Whitted Specular",
        "Whitted Reflection", "Whitted Refraction", "CryptoObject00", "CryptoObject01",
        "CryptoObject02", "CryptoMaterial00", "CryptoMaterial01", "CryptoMaterial02",
    }  # fmt: skip
    layer = next(name.split(".")[0] for name in channels)
    terms = ("Env", "Whitted Ambient", "Whitted Diffuse", "Whitted Specular",
             "Whitted Reflection", "Whitted Refraction")  # fmt: skip
    total = sum(channels[f"{layer}.{term}.G"] for term in terms)
    np.testing.assert_allclose(total, channels[f"{layer}.Combined.G"], rtol=2e-3, atol=2e-3)
    assert any(key.endswith("/manifest") and '"Red"' in value for key, value in metadata.items())


def test_a_farm_managers_tile_job_gets_its_log_lines_and_cropped_border(tmp_path):
    """What Flamenco, Deadline or a shell loop parse from plain `blender -b`: `Fra:` lines with
    the tile progress, the `Saved:` line; and a tile job's border (set by a script, with
    Crop to Render Region) is honoured, the file cropped to it."""
    border = (
        "import bpy; r = bpy.context.scene.render; r.use_border = r.use_crop_to_border = True; "
        "r.border_min_x, r.border_max_x, r.border_min_y, r.border_max_y = 0.5, 1.0, 0.0, 0.5"
    )
    run = blender_34(
        str(SAMPLE), "--addons", "whitted", "-E", "WHITTED", "--python-expr", border,
        "-o", f"{tmp_path}/tile_####", "-F", "PNG", "-f", "1",
    )  # fmt: skip
    assert run.returncode == 0, run.stdout
    tiles = [line for line in run.stdout.splitlines() if line.startswith("Fra:1 ")]
    assert any("| Whitted | Tile 1/" in line for line in tiles), run.stdout[-2000:]
    assert f"Saved: '{tmp_path}/tile_0001.png'" in run.stdout
    assert Image.open(tmp_path / "tile_0001.png").size == (160, 120)  # half of 320 x 240


def test_an_animation_renders_frame_by_frame(tmp_path):
    run = blender_34(
        str(SAMPLE), "--addons", "whitted", "-E", "WHITTED", "-o", f"{tmp_path}/frame_####",
        "-F", "PNG", "-s", "3", "-e", "4", "-a",
    )  # fmt: skip
    assert run.returncode == 0 and "Traceback" not in run.stdout + run.stderr, run.stdout
    assert sorted(p.name for p in tmp_path.iterdir()) == ["frame_0003.png", "frame_0004.png"]


def test_a_checkout_link_loads_core_as_the_add_ons_own_and_keeps_kernels_in_the_checkout():
    """As a user's Blender loads a linked checkout: no checkout on the module path and no
    cache folder named. `core` is then the add-on's subpackage, no top-level `core` appears,
    and kernels go under the checkout."""
    site = ROOT / ".venv" / "lib" / "python3.11" / "site-packages"
    env = {k: v for k, v in os.environ.items() if k != "WHITTED_CACHE_DIR"}
    env["PYTHONPATH"] = str(site)
    probe = (
        "import os, sys; print('CORE', sys.modules['whitted.core'].__file__,"
        " 'core' in sys.modules, os.environ['WHITTED_CACHE_DIR'])"
    )
    run = subprocess.run(
        [shutil.which("blender"), "-b", "--python-use-system-env", "--addons", "whitted",
         "--python-expr", probe],
        env=env, capture_output=True, text=True, timeout=300,
    )  # fmt: skip
    assert run.returncode == 0, run.stdout + run.stderr
    line = next(line for line in run.stdout.splitlines() if line.startswith("CORE "))
    assert line.split() == ["CORE", str(ROOT / "core" / "__init__.py"), "False",
                            str(ROOT / ".cache" / "kernels")]  # fmt: skip


@pytest.mark.parametrize(
    "breakage, messages",
    [
        # The user's mistake: a clear message naming the object and the field
        ("import bpy; bpy.data.objects['Blue'].scale = (0, 1, 1)",
         ["Error: Whitted: sphere 'Blue': world_from_object: is singular", "non-zero scale"]),
        # Whitted's own failure (here the export raises), not a scene error
        ("import sys; sys.modules['whitted.export'].convert = lambda *a, **k: 1 / 0",
         ["Whitted: the render failed: ZeroDivisionError: division by zero"]),
    ],
    ids=["scene error", "engine exception"],
)  # fmt: skip
def test_a_failed_render_exits_non_zero_and_writes_no_frame(tmp_path, breakage, messages):
    """A farm sees only the exit status: it must be non-zero, with no blank frame left
    behind (an engine exception used to give exit 0 and a blank frame)."""
    run = blender_34(
        str(SAMPLE), "--addons", "whitted", "--python-expr", breakage,
        "-E", "WHITTED", "-o", f"{tmp_path}/broken_####", "-F", "PNG", "-f", "1",
    )  # fmt: skip
    output = run.stdout + run.stderr
    assert run.returncode != 0, output
    for message in messages:
        assert message in output
    assert "Traceback" not in run.stdout
    assert not list(tmp_path.glob("broken_*")), "a frame was written"


AUTO_SMOOTH_RERENDER = """
import sys, bpy
out = sys.argv[-1]
for obj in list(bpy.data.objects):
    bpy.data.objects.remove(obj)
scene = bpy.context.scene
scene.render.engine = "WHITTED"
scene.render.resolution_x = scene.render.resolution_y = 24
bpy.ops.object.camera_add(location=(0, -5, 0), rotation=(1.5707963, 0, 0))
scene.camera = bpy.context.active_object
bpy.ops.mesh.primitive_uv_sphere_add(segments=8, ring_count=6)
ball = bpy.context.active_object
bpy.ops.object.shade_smooth()
ball.data.use_auto_smooth = True
ball.data.auto_smooth_angle = 0.1  # every edge sharp: faceted
bpy.ops.object.light_add(type="POINT", location=(2, -4, 3))
bpy.context.active_object.data.energy = 3000
def render(name):
    scene.render.filepath = f"{out}/{name}.png"
    bpy.ops.render.render(write_still=True)
if sys.argv[-2] == "twice":
    render("faceted")
ball.data.auto_smooth_angle = 3.14  # no edge sharp: smooth
render("smooth")
"""


def test_a_re_render_sees_an_auto_smooth_change(tmp_path):
    """Blender 3.4 keeps Auto Smooth on the mesh: a second render in one session changed
    nothing, as the mesh cache did not know it. Now it makes the picture a new session
    makes."""
    for how, folder in (("twice", tmp_path / "session"), ("once", tmp_path / "fresh")):
        folder.mkdir()
        run = blender_34("--addons", "whitted", "--python-expr", AUTO_SMOOTH_RERENDER,
                         "--", how, str(folder))  # fmt: skip
        assert run.returncode == 0, run.stdout + run.stderr
    faceted, smooth = (np.asarray(Image.open(tmp_path / "session" / f"{n}.png")) for n in
                       ("faceted", "smooth"))  # fmt: skip
    fresh = np.asarray(Image.open(tmp_path / "fresh" / "smooth.png"))
    assert not np.array_equal(faceted, smooth)
    np.testing.assert_array_equal(smooth, fresh)


def test_the_caustic_photon_pass_shows_its_progress_in_the_log(tmp_path):
    """The report's mirror balls with Light Paths > Caustics > Mirrors turned on: their CS488
    light sends photons, and `blender -b`'s `Fra:` lines show the pass going before the
    tiles; the summary line names it."""
    turn_on = (
        "import bpy; s = bpy.context.scene; w = s.whitted; w.use_caustics_reflective = True; "
        "w.use_auto_photons = False; w.caustic_photons = 40000; s.render.resolution_percentage = 25"
    )
    run = blender_34(
        str(SAMPLE.parent / "mirror.blend"), "--addons", "whitted", "-E", "WHITTED",
        "--python-expr", turn_on, "-o", f"{tmp_path}/mirror_####", "-F", "PNG", "-f", "1",
    )  # fmt: skip
    assert run.returncode == 0, run.stdout[-2000:]
    lines = [line for line in run.stdout.splitlines() if line.startswith("Fra:1 ")]
    passes = [i for i, line in enumerate(lines) if "| Whitted | Caustic photons " in line]
    tiles = [i for i, line in enumerate(lines) if "| Whitted | Tile " in line]
    assert len(passes) > 1 and tiles and max(passes) < min(tiles), run.stdout[-3000:]
    assert re.search(r"Caustic photons ([\d,]+)/\1", lines[passes[-1]]), lines[passes[-1]]
    assert "photons traced" in run.stdout
