"""Passes, holdouts and view layers through Blender: the Render Layers node offers the passes a
view layer asks for, and a multilayer EXR that Blender writes (read back by tests/support/exr,
checked against Blender's own files) holds them per view layer, each with its own
collections, holdouts and passes. Values against closed forms of a tagged sphere over a
plane under an orthographic camera looking straight down, one ray per pixel: pixel (px, py)
looks down at x = -2 + 0.1 (px + 1/2), y = 1.5 - 0.1 (py + 1/2)."""

import math
import sys

import numpy as np
import pytest

from core.passes import crypto_mask
from tests.blender.conftest import clear_scene
from tests.support.exr import read_exr

WIDTH, HEIGHT = 40, 30
CAMERA_Z, FLOOR_Z = 5.0, -1.5
# Whitted's terms, Cycles' Environment and Emission (their names in the running Blender)
TERMS = ("Env", "Whitted Ambient", "Whitted Diffuse", "Whitted Specular", "Whitted Reflection",
         "Whitted Refraction", "Emit")  # fmt: skip


def named(name: str) -> str:
    """Cycles' name for the pass Blender before 5.0 called `name`, in this Blender
    (tests/blender/test_pass_names.py checks the names against what Cycles writes)."""
    return sys.modules["whitted.compat"].pass_name(name)


@pytest.fixture
def ball_scene(bpy_with_whitted):
    bpy = bpy_with_whitted
    scene = clear_scene(bpy)
    for datablocks in (bpy.data.materials, bpy.data.collections):
        for datablock in list(datablocks):
            datablocks.remove(datablock)
    scene.render.engine = "WHITTED"
    scene.render.resolution_x, scene.render.resolution_y = WIDTH, HEIGHT
    scene.render.resolution_percentage = 100
    scene.render.film_transparent = False
    scene.whitted.pixel_samples = 1
    scene.whitted.pixel_sampling = "GRID"  # the pixel's centre (another test may jitter)
    scene.world = None  # no World left by another test: a black background, no sky light
    for layer in list(scene.view_layers)[1:]:
        scene.view_layers.remove(layer)
    bpy.ops.object.camera_add(location=(0.0, 0.0, CAMERA_Z), rotation=(0.0, 0.0, 0.0))
    scene.camera = bpy.context.active_object
    scene.camera.data.type, scene.camera.data.ortho_scale = "ORTHO", 4.0
    bpy.ops.object.light_add(type="SUN", location=(0.0, 0.0, 8.0))
    balls = bpy.data.collections.new("Balls")
    scene.collection.children.link(balls)
    bpy.ops.mesh.primitive_uv_sphere_add(radius=1.0)
    ball = bpy.context.active_object
    ball.name, ball.whitted.shape, ball.pass_index = "Ball", "SPHERE", 3
    chalk = bpy.data.materials.new("Chalk")
    chalk.pass_index = 6
    ball.data.materials.append(chalk)
    for collection in list(ball.users_collection):
        collection.objects.unlink(ball)
    balls.objects.link(ball)
    bpy.ops.mesh.primitive_plane_add(size=12.0, location=(0.0, 0.0, FLOOR_Z))
    bpy.context.active_object.name = "Floor"
    yield scene
    # What the tests changed that outlives clear_scene: the compositor, the file format
    if hasattr(scene, "compositing_node_group"):
        scene.compositing_node_group = None
    else:
        scene.use_nodes = False
    settings = scene.render.image_settings
    if hasattr(settings, "media_type"):
        settings.media_type = "IMAGE"
    settings.file_format = "PNG"


def pixel_ground(px, py):
    """(x, y) under pixel (px, py), and r^2 there."""
    x, y = -2.0 + 0.1 * (px + 0.5), 1.5 - 0.1 * (py + 0.5)
    return x, y, x * x + y * y


def render_exr(bpy, scene, path):
    settings = scene.render.image_settings
    if hasattr(settings, "media_type"):  # Blender 5: multilayer is a kind of media
        settings.media_type = "MULTI_LAYER_IMAGE"
    settings.file_format = "OPEN_EXR_MULTILAYER"
    settings.color_depth = "32"
    scene.render.filepath = str(path)
    bpy.ops.render.render(write_still=True)
    return read_exr(path)


def compositor(bpy, scene):
    if hasattr(scene, "compositing_node_group"):  # Blender 5
        tree = bpy.data.node_groups.new("Compositing", "CompositorNodeTree")
        scene.compositing_node_group = tree
        return tree
    scene.use_nodes = True
    return scene.node_tree


def test_the_render_layers_node_offers_the_passes_the_view_layer_asks_for(ball_scene):
    import bpy

    layer = ball_scene.view_layers[0]
    for switch in ("use_pass_z", "use_pass_mist", "use_pass_object_index",
                   "use_pass_cryptomatte_material"):  # fmt: skip
        setattr(layer, switch, True)
    layer.whitted.use_pass_terms = True
    tree = compositor(bpy, ball_scene)
    node = tree.nodes.new("CompositorNodeRLayers")
    offered = {socket.name for socket in node.outputs if socket.enabled}
    assert offered == {
        "Image", "Alpha", "Depth", "Mist", named("IndexOB"), "CryptoMaterial00", "CryptoMaterial01",
        "CryptoMaterial02", *TERMS[1:-1],
    }  # fmt: skip
    assert "Normal" not in offered and "CryptoObject00" not in offered


def test_the_passes_reach_blenders_multilayer_exr_exactly(ball_scene, tmp_path):
    import bpy

    layer = ball_scene.view_layers[0]
    for switch in ("use_pass_z", "use_pass_normal", "use_pass_object_index",
                   "use_pass_material_index", "use_pass_cryptomatte_object",
                   "use_pass_cryptomatte_material", "use_pass_environment",
                   "use_pass_mist", "use_pass_emit"):  # fmt: skip
        setattr(layer, switch, True)
    layer.whitted.use_pass_terms = True
    if ball_scene.world is None:
        ball_scene.world = bpy.data.worlds.new("World")
    mist = ball_scene.world.mist_settings
    mist.start, mist.depth, mist.falloff = 3.0, 4.0, "LINEAR"
    channels, metadata = render_exr(bpy, ball_scene, tmp_path / "passes.exr")

    def get(name):
        return channels[f"ViewLayer.{name}"]

    on_ball = 0
    for py in range(HEIGHT):
        for px in range(WIDTH):
            x, y, r2 = pixel_ground(px, py)
            if abs(r2 - 1.0) < 1e-3:
                continue  # the rim: too close to call
            depth, index, material = CAMERA_Z - FLOOR_Z, 0, 0
            normal = (0.0, 0.0, 1.0)
            if r2 < 1.0:
                z = math.sqrt(1.0 - r2)
                depth, index, material, normal = CAMERA_Z - z, 3, 6, (x, y, z)
                on_ball += 1
            assert get("Depth.Z")[py, px] == pytest.approx(depth, rel=1e-6), (px, py)
            # Mist from the World's Mist Pass settings: orthographic, along the view
            expected_mist = min(1.0, max(0.0, (depth - 3.0) / 4.0))
            assert get("Mist.Z")[py, px] == pytest.approx(expected_mist, abs=1e-6)
            assert get(f"{named('IndexOB')}.X")[py, px] == index
            assert get(f"{named('IndexMA')}.X")[py, px] == material
            got = [get(f"Normal.{axis}")[py, px] for axis in "XYZ"]
            np.testing.assert_allclose(got, normal, atol=1e-5)
    assert on_ball > 200
    crypto = np.stack([get(f"CryptoObject0{k // 4}.{'RGBA'[k % 4]}") for k in range(12)], -1)
    _, _, r2 = np.vectorize(pixel_ground)(*np.meshgrid(range(WIDTH), range(HEIGHT)))
    clear = np.abs(r2 - 1.0) > 1e-3
    np.testing.assert_array_equal(crypto_mask(crypto, "Ball")[clear], (r2 < 1.0)[clear])
    manifests = [v for k, v in metadata.items() if k.endswith("/manifest")]
    names = [v for k, v in metadata.items() if k.startswith("cryptomatte/") and k.endswith("/name")]
    assert sorted(names) == ["ViewLayer.CryptoMaterial", "ViewLayer.CryptoObject"]
    assert any('"Ball"' in m and '"Floor"' in m for m in manifests)
    assert any('"Chalk"' in m for m in manifests)
    for channel in "RGB":
        total = sum(get(f"{named(term)}.{channel}") for term in TERMS)
        np.testing.assert_allclose(total, get(f"Combined.{channel}"), rtol=1e-5, atol=1e-6)


def test_each_view_layer_renders_its_own_collections_holdouts_and_passes(ball_scene, tmp_path):
    import bpy

    ball_scene.view_layers[0].use_pass_z = True
    no_balls = ball_scene.view_layers.new("NoBalls")
    no_balls.layer_collection.children["Balls"].exclude = True
    no_balls.use_pass_normal = True
    held = ball_scene.view_layers.new("Held")
    held.layer_collection.children["Balls"].holdout = True
    channels, _ = render_exr(bpy, ball_scene, tmp_path / "layers.exr")
    assert "ViewLayer.Depth.Z" in channels and "NoBalls.Normal.Z" in channels
    assert "NoBalls.Depth.Z" not in channels and "Held.Normal.Z" not in channels
    grid = np.meshgrid(range(WIDTH), range(HEIGHT))
    _, _, r2 = np.vectorize(pixel_ground)(*grid)
    ball, floor = r2 < 1.0 - 1e-3, r2 > 1.0 + 1e-3
    assert np.all(channels["NoBalls.Normal.Z"] == 1.0)  # only the floor, straight up
    assert np.all(channels["NoBalls.Combined.A"] == 1.0)
    # The holdout: an exact hole where the ball is, though the film is opaque
    assert np.all(channels["Held.Combined.A"][ball] == 0.0)
    assert np.all(channels["Held.Combined.R"][ball] == 0.0)
    assert np.all(channels["Held.Combined.A"][floor] == 1.0)
    for channel in "RGB":  # the floor shows as in the first layer, the ball's shadow included
        np.testing.assert_array_equal(
            channels[f"Held.Combined.{channel}"][floor],
            channels[f"ViewLayer.Combined.{channel}"][floor],
        )
    depth = channels["ViewLayer.Depth.Z"]
    np.testing.assert_allclose(depth[floor], CAMERA_Z - FLOOR_Z, rtol=1e-6)


def test_a_transparent_film_carries_alpha_into_png_and_exr(ball_scene, tmp_path):
    import bpy
    from PIL import Image

    ball_scene.render.film_transparent = True
    ball_scene.objects["Floor"].hide_render = True
    ball_scene.whitted.pixel_samples = 3
    channels, _ = render_exr(bpy, ball_scene, tmp_path / "film.exr")
    expected = np.array([[sample_coverage(px, py) for px in range(WIDTH)] for py in range(HEIGHT)])
    np.testing.assert_array_equal(channels["ViewLayer.Combined.A"], expected.astype(np.float32))
    settings = ball_scene.render.image_settings
    if hasattr(settings, "media_type"):
        settings.media_type = "IMAGE"
    settings.file_format, settings.color_mode = "PNG", "RGBA"
    ball_scene.render.filepath = str(tmp_path / "film.png")
    bpy.ops.render.render(write_still=True)
    alpha = np.asarray(Image.open(tmp_path / "film.png"))[..., 3]
    np.testing.assert_allclose(alpha / 255.0, expected, atol=0.5 / 255.0 + 1e-9)


def test_show_in_renders_and_object_holdouts_are_honoured(ball_scene, tmp_path):
    import bpy

    ball = ball_scene.objects["Ball"]
    ball_scene.view_layers[0].use_pass_z = True
    ball.is_holdout = True
    channels, _ = render_exr(bpy, ball_scene, tmp_path / "holdout.exr")
    _, _, r2 = np.vectorize(pixel_ground)(*np.meshgrid(range(WIDTH), range(HEIGHT)))
    assert np.all(channels["ViewLayer.Combined.A"][r2 < 1.0 - 1e-3] == 0.0)
    ball.is_holdout = False
    ball.hide_render = True
    channels, _ = render_exr(bpy, ball_scene, tmp_path / "hidden.exr")
    np.testing.assert_allclose(channels["ViewLayer.Depth.Z"], CAMERA_Z - FLOOR_Z, rtol=1e-6)


def sample_coverage(px, py, n=3):
    """Share of pixel (px, py)'s n x n grid rays that meet the ball (straight down)."""
    inside = 0
    for s in range(n * n):
        x = -2.0 + 0.1 * (px + (s % n + 0.5) / n)
        y = 1.5 - 0.1 * (py + (s // n + 0.5) / n)
        inside += x * x + y * y < 1.0
    return inside / (n * n)


def test_blenders_cryptomatte_node_picks_an_object_by_its_name(ball_scene, tmp_path):
    """Blender's own Cryptomatte node, reading Whitted's passes and manifest from the render
    result, gives the ball's exact anti-aliased coverage as its matte."""
    import bpy

    ball_scene.whitted.pixel_samples = 3
    ball_scene.view_layers[0].use_pass_cryptomatte_object = True
    tree = compositor(bpy, ball_scene)
    for node in list(tree.nodes):
        tree.nodes.remove(node)
    if hasattr(ball_scene, "compositing_node_group"):  # Blender 5: the group's output
        tree.interface.new_socket("Image", in_out="OUTPUT", socket_type="NodeSocketColor")
        output = tree.nodes.new("NodeGroupOutput").inputs[0]
    else:
        output = tree.nodes.new("CompositorNodeComposite").inputs["Image"]
    layers = tree.nodes.new("CompositorNodeRLayers")
    crypto = tree.nodes.new("CompositorNodeCryptomatteV2")
    crypto.source, crypto.scene, crypto.matte_id = "RENDER", ball_scene, "Ball"
    tree.links.new(layers.outputs["Image"], crypto.inputs["Image"])
    tree.links.new(crypto.outputs["Matte"], output)
    settings = ball_scene.render.image_settings
    if hasattr(settings, "media_type"):
        settings.media_type = "IMAGE"
    settings.file_format, settings.color_depth = "OPEN_EXR", "32"
    ball_scene.render.filepath = str(tmp_path / "matte.exr")
    bpy.ops.render.render(write_still=True)
    matte = read_exr(tmp_path / "matte.exr")[0]["R"]
    expected = np.array([[sample_coverage(px, py) for px in range(WIDTH)] for py in range(HEIGHT)])
    np.testing.assert_allclose(matte, expected, atol=1e-6)
    assert ((expected > 0) & (expected < 1)).sum() > 20  # the rim is in it
