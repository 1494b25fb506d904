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


def blender_writes(bpy, rgba, path, codec: str, depth: str) -> None:
    """`rgba` (row 0 at the top) saved by Blender's OpenEXR library with `codec`, in half
    ("16") or float ("32")."""
    image = bpy.data.images.new("written", WIDTH, HEIGHT, alpha=True, float_buffer=True)
    image.pixels[:] = rgba[::-1].ravel()
    settings = bpy.context.scene.render.image_settings
    if hasattr(settings, "media_type"):
        settings.media_type = "IMAGE"
    settings.file_format, settings.color_depth = "OPEN_EXR", depth
    settings.exr_codec, settings.color_mode = codec, "RGBA"
    image.save_render(str(path), scene=bpy.context.scene)
    bpy.data.images.remove(image)


def test_blender_reads_the_files_core_writes(bpy_with_whitted, tmp_path):
    rgba = pixels()
    path = write_exr(tmp_path / "core.exr", {c: rgba[..., i] for i, c in enumerate("RGBA")})
    image = bpy_with_whitted.data.images.load(str(path))
    loaded = np.array(image.pixels[:], np.float32).reshape(HEIGHT, WIDTH, 4)[::-1]
    np.testing.assert_array_equal(loaded, rgba)


@pytest.mark.parametrize("codec", ["ZIP", "NONE", "ZIPS"])
def test_the_tests_reader_reads_the_files_blender_writes(bpy_with_whitted, tmp_path, codec):
    rgba = pixels()
    blender_writes(bpy_with_whitted, rgba, tmp_path / "blender.exr", codec, "32")
    channels, _ = read_exr(tmp_path / "blender.exr")
    np.testing.assert_array_equal(np.stack([channels[c] for c in "RGBA"], -1), rgba)


@pytest.mark.parametrize("codec, depth", [("ZIP", "32"), ("NONE", "32"), ("ZIPS", "16"),
                                          ("RLE", "16"), ("RLE", "32"), ("PIZ", "16")])  # fmt: skip
def test_a_texture_blender_wrote_is_read_at_its_values(bpy_with_whitted, tmp_path, codec, depth):
    """core.textures reads OpenEXR textures itself (Pillow reads none): Blender's files,
    half and float, of each codec the reader takes; another codec is named, not misread."""
    from core.textures import ImageFileError, read_rgb

    rgba = pixels()
    blender_writes(bpy_with_whitted, rgba, tmp_path / "texture.exr", codec, depth)
    if codec == "PIZ":
        with pytest.raises(ImageFileError, match="uses PIZ compression; save it with ZIP"):
            read_rgb(tmp_path / "texture.exr")
        return
    expected = rgba[..., :3].astype(np.float16 if depth == "16" else np.float32)
    np.testing.assert_array_equal(read_rgb(tmp_path / "texture.exr"), expected.astype(float))
