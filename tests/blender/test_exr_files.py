"""The two EXR codes of this project against Blender's own OpenEXR library: Blender reads
core.exr's files pixel for pixel, and tests/support/exr.py reads the files Blender writes,
with each codec Whitted's tests meet."""

import numpy as np
import pytest

from core.exr import write_exr
from tests.support.exr import read_exr

HEIGHT, WIDTH = 21, 34


def pixels():
    return np.random.default_rng(3).random((HEIGHT, WIDTH, 4)).astype(np.float32) * 10


def test_blender_reads_the_files_core_writes(bpy_with_whitted, tmp_path):
    rgba = pixels()
    path = write_exr(tmp_path / "core.exr", {c: rgba[..., i] for i, c in enumerate("RGBA")})
    image = bpy_with_whitted.data.images.load(str(path))
    loaded = np.array(image.pixels[:], np.float32).reshape(HEIGHT, WIDTH, 4)[::-1]
    np.testing.assert_array_equal(loaded, rgba)


@pytest.mark.parametrize("codec", ["ZIP", "NONE", "ZIPS"])
def test_the_tests_reader_reads_the_files_blender_writes(bpy_with_whitted, tmp_path, codec):
    bpy = bpy_with_whitted
    rgba = pixels()
    image = bpy.data.images.new("written", WIDTH, HEIGHT, alpha=True, float_buffer=True)
    image.pixels[:] = rgba[::-1].ravel()
    settings = bpy.context.scene.render.image_settings
    if hasattr(settings, "media_type"):
        settings.media_type = "IMAGE"
    settings.file_format, settings.color_depth = "OPEN_EXR", "32"
    settings.exr_codec, settings.color_mode = codec, "RGBA"
    image.save_render(str(tmp_path / "blender.exr"), scene=bpy.context.scene)
    channels, _ = read_exr(tmp_path / "blender.exr")
    np.testing.assert_array_equal(np.stack([channels[c] for c in "RGBA"], -1), rgba)
