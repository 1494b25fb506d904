"""The add-on inside Blender 5.0 (the bpy module): registration, pixels, tiles, cancel, errors."""

import sys

import numpy as np
import pytest
from PIL import Image

import core
from tests.blender.versions import SUPPORTED
from tests.support.blender_reference import expected_pixels, sample_grid

pytestmark = pytest.mark.bpy


def render_to_array(bpy, scene, path):
    scene.render.filepath = str(path)
    bpy.ops.render.render(write_still=True)
    return np.asarray(Image.open(path), dtype=float)


def engine_class():
    return sys.modules["whitted.engine"].WhittedRenderEngine


def final_render():
    """The engine's module for F12 and `blender -b` (its hooks are patched below)."""
    return sys.modules["whitted.engine.final"]


def test_engine_is_registered_and_listed(bpy_with_whitted):
    bpy = bpy_with_whitted
    assert bpy.app.version[:2] in SUPPORTED  # also run inside Blender 3.4
    scene = bpy.context.scene
    # The engine enum is dynamic: Blender lists its valid items when given an invalid one
    with pytest.raises(TypeError, match=r"'WHITTED'"):
        scene.render.engine = "NOT_AN_ENGINE"
    scene.render.engine = "WHITTED"
    assert scene.render.engine == "WHITTED"
    assert engine_class().bl_label == "Whitted"


def test_sample_scene_pixels_match_the_reference(sample_scene, bpy_with_whitted, tmp_path):
    image = render_to_array(bpy_with_whitted, sample_scene, tmp_path / "spheres.png")
    assert image.shape == (120, 160, 4)
    pixels = sample_grid(160, 120, 6)
    expected = expected_pixels(sample_scene, pixels)
    got = np.array([image[py, px, :3] for px, py in pixels])
    np.testing.assert_allclose(got, expected, atol=1.6)
    assert np.all(image[..., 3] == 255)


def test_every_pixel_is_written_by_exactly_one_tile(sample_scene, bpy_with_whitted, monkeypatch):
    final = final_render()
    written = np.zeros((120, 160), int)
    original = final.TileWriter.write

    def record(writer, tile, pixels):
        written[tile.y : tile.y + tile.height, tile.x : tile.x + tile.width] += 1
        original(writer, tile, pixels)

    monkeypatch.setattr(final.TileWriter, "write", record)
    sample_scene.whitted.tile_size = 24  # does not divide 160 x 120: edge tiles are partial
    bpy_with_whitted.ops.render.render()
    assert np.all(written == 1)


def test_render_border_is_rendered_in_place(sample_scene, bpy_with_whitted, tmp_path):
    full = render_to_array(bpy_with_whitted, sample_scene, tmp_path / "full.png")
    render = sample_scene.render
    render.use_border, render.use_crop_to_border = True, True
    render.border_min_x, render.border_max_x = 0.213, 0.77
    render.border_min_y, render.border_max_y = 0.1, 0.633
    cropped = render_to_array(bpy_with_whitted, sample_scene, tmp_path / "crop.png")
    # Blender's border in pixels: x 34..122, rows 12..74 from the bottom = 45..107 from the top
    assert cropped.shape == (63, 89, 4)
    np.testing.assert_array_equal(cropped, full[45:108, 34:123])


def test_cancel_from_test_break_stops_within_one_tile(sample_scene, bpy_with_whitted, monkeypatch):
    final = final_render()
    tiles = []
    original = final.TileWriter.write

    def record(writer, tile, pixels):
        tiles.append(tile)
        original(writer, tile, pixels)

    monkeypatch.setattr(final.TileWriter, "write", record)
    # Blender's own test_break cannot be overridden from Python; patch the hook that calls it
    monkeypatch.setattr(final, "cancelled", lambda engine: len(tiles) >= 1)
    sample_scene.whitted.tile_size = 8
    sample_scene.render.threads_mode = "FIXED"
    sample_scene.render.threads = 2
    bpy_with_whitted.ops.render.render()
    assert 1 <= len(tiles) <= 2  # the tile that saw the cancel, and the other thread's
    monkeypatch.undo()
    tiles.clear()
    bpy_with_whitted.ops.render.render()  # Blender is still usable and renders in full


def test_zero_scale_sphere_is_reported_by_name(sample_scene, bpy_with_whitted):
    sample_scene.objects["Red"].scale = (1.0, 0.0, 1.0)
    with pytest.raises(RuntimeError) as error:
        bpy_with_whitted.ops.render.render()
    message = str(error.value)
    assert "sphere 'Red'" in message and "non-zero scale" in message
    assert "Traceback" not in message
    sample_scene.objects["Red"].scale = (1.0, 1.0, 1.0)
    assert bpy_with_whitted.ops.render.render() == {"FINISHED"}


def test_missing_camera_is_reported(sample_scene, bpy_with_whitted):
    bpy = bpy_with_whitted
    sample_scene.camera = None
    # Blender itself refuses before any engine runs ...
    with pytest.raises(RuntimeError, match="no camera"):
        bpy.ops.render.render()
    # ... and our exporter, called on its own, names the scene and the field
    export = sys.modules["whitted.export"]
    with pytest.raises(core.SceneError, match=r"scene 'Scene': camera: there is no active camera"):
        export.convert(bpy.context.evaluated_depsgraph_get())


def test_zero_resolution_is_reported(sample_scene, bpy_with_whitted):
    export = sys.modules["whitted.export"]
    # Blender clamps resolution to >= 4 pixels and the scale to >= 1 %: 4 px at 1 % is 0 pixels
    sample_scene.render.resolution_x = 0
    assert sample_scene.render.resolution_x >= 4
    sample_scene.render.resolution_x, sample_scene.render.resolution_percentage = 4, 1
    with pytest.raises(core.SceneError, match=r"render resolution_x: 0 pixels after the 1% scale"):
        export.settings.convert(sample_scene)
    with pytest.raises(RuntimeError, match="Image too small|resolution"):
        bpy_with_whitted.ops.render.render()


def test_orthographic_camera_pixels_match_the_reference(sample_scene, bpy_with_whitted, tmp_path):
    sample_scene.camera.data.type = "ORTHO"
    sample_scene.camera.data.ortho_scale = 9.0
    image = render_to_array(bpy_with_whitted, sample_scene, tmp_path / "ortho.png")
    pixels = sample_grid(160, 120, 6)
    expected = expected_pixels(sample_scene, pixels)
    got = np.array([image[py, px, :3] for px, py in pixels])
    np.testing.assert_allclose(got, expected, atol=1.6)
    # Not the perspective picture, and not empty: the spheres are in view
    assert np.ptp(got) > 50


def test_orthographic_lens_shift_is_exported(sample_scene, bpy_with_whitted):
    export = sys.modules["whitted.export"]
    data = sample_scene.camera.data
    data.type, data.ortho_scale, data.shift_x, data.shift_y = "ORTHO", 8.0, 0.25, -0.1
    depsgraph = bpy_with_whitted.context.evaluated_depsgraph_get()
    camera = export.camera.convert(sample_scene, depsgraph, export.settings.convert(sample_scene))
    # Blender's shift is in units of the larger side (the width, 8.0 here): in half-widths
    # and half-heights of a 160 x 120 image that is 2 shift_x and 2 shift_y * 160 / 120
    assert camera.projection == "orthographic"
    assert camera.ortho_height == pytest.approx(8.0 * 120 / 160)
    assert camera.shift == pytest.approx((0.5, -0.2 * 160 / 120))


def test_panoramic_camera_is_reported(sample_scene, bpy_with_whitted):
    sample_scene.camera.data.type = "PANO"
    with pytest.raises(RuntimeError, match=r"camera 'Camera': lens type: is PANO;.*Orthographic"):
        bpy_with_whitted.ops.render.render()


def test_non_camera_object_as_scene_camera_is_reported(sample_scene, bpy_with_whitted):
    export = sys.modules["whitted.export"]
    sample_scene.camera = sample_scene.objects["Key"]  # Blender accepts any object here
    depsgraph = bpy_with_whitted.context.evaluated_depsgraph_get()
    with pytest.raises(core.SceneError, match=r"camera 'Key': type: is a LIGHT object"):
        export.camera.convert(sample_scene, depsgraph, export.settings.convert(sample_scene))


def render_float(bpy, scene, path):
    """Render to a 32-bit float OpenEXR and read it back through Blender: exact pixels,
    rows bottom-up as Blender stores them."""
    settings = scene.render.image_settings
    settings.file_format, settings.color_depth = "OPEN_EXR", "32"
    scene.render.filepath = str(path)
    bpy.ops.render.render(write_still=True)
    image = bpy.data.images.load(str(path))
    pixels = np.empty(image.size[0] * image.size[1] * 4, np.float32)
    image.pixels.foreach_get(pixels)
    shape = (image.size[1], image.size[0], 4)
    bpy.data.images.remove(image)
    return pixels.reshape(shape)


def test_four_border_renders_stitch_into_the_whole_frame_bit_for_bit(
    sample_scene, bpy_with_whitted, tmp_path
):
    """How a farm splits a frame across machines: four render borders, cropped, stitched."""
    bpy = bpy_with_whitted
    sample_scene.whitted.pixel_samples = 2
    sample_scene.whitted.pixel_sampling = "JITTERED"
    whole = render_float(bpy, sample_scene, tmp_path / "whole.exr")
    render = sample_scene.render
    render.use_border, render.use_crop_to_border = True, True
    stitched = np.zeros_like(whole)
    height, width = whole.shape[:2]
    for x0, y0 in ((0, 0), (0.5, 0), (0, 0.5), (0.5, 0.5)):
        render.border_min_x, render.border_max_x = x0, x0 + 0.5
        render.border_min_y, render.border_max_y = y0, y0 + 0.5
        part = render_float(bpy, sample_scene, tmp_path / f"part_{x0}_{y0}.exr")
        row, column = int(y0 * height), int(x0 * width)
        stitched[row : row + part.shape[0], column : column + part.shape[1]] = part
    np.testing.assert_array_equal(stitched, whole)


def test_a_border_without_crop_fills_its_region_of_the_whole_frame(
    sample_scene, bpy_with_whitted, tmp_path
):
    bpy = bpy_with_whitted
    whole = render_float(bpy, sample_scene, tmp_path / "whole.exr")
    render = sample_scene.render
    render.use_border, render.use_crop_to_border = True, False
    render.border_min_x, render.border_max_x = 0.25, 0.75
    render.border_min_y, render.border_max_y = 0.5, 1.0
    framed = render_float(bpy, sample_scene, tmp_path / "framed.exr")
    assert framed.shape == whole.shape
    height, width = whole.shape[:2]
    rows, columns = slice(height // 2, height), slice(width // 4, 3 * width // 4)
    np.testing.assert_array_equal(framed[rows, columns], whole[rows, columns])
    outside = np.ones(whole.shape[:2], bool)
    outside[rows, columns] = False
    assert np.all(framed[outside] == 0.0)  # Blender leaves the rest empty


def test_film_transparent_writes_the_background_transparent(
    sample_scene, bpy_with_whitted, tmp_path
):
    """Film > Transparent: the sky's pixels have alpha 0 in the PNG, the ground's and balls'
    255 (the sample's ground fills the lower part of the frame)."""
    sample_scene.render.film_transparent = True
    sample_scene.render.image_settings.color_mode = "RGBA"
    image = render_to_array(bpy_with_whitted, sample_scene, tmp_path / "clear.png")
    assert image[0, 0, 3] == 0 and image[-1, -1, 3] == 255
    assert np.all(image[image[..., 3] == 0][:, :3] == 0)
    sample_scene.render.film_transparent = False
    image = render_to_array(bpy_with_whitted, sample_scene, tmp_path / "opaque.png")
    assert np.all(image[..., 3] == 255)
