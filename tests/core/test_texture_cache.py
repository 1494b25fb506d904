"""Decoded texture files are kept for the next compile (core.textures): the same file gives
the same pixels without being read again, an edited file is read again, and the cached
pixels cannot be changed by a user of them. Textures handed over as pixels (Blender's
images) are kept by their content: the same pixels once, any changed pixel again."""

import os

import numpy as np
import pytest
from PIL import Image

from core import SceneError, Texture
from core.textures import load_texture


def write_png(path, colour):
    Image.fromarray(np.full((4, 6, 3), colour, np.uint8)).save(path)


def test_an_unchanged_file_is_decoded_once_and_an_edited_one_again(tmp_path):
    path = tmp_path / "t.png"
    write_png(path, 200)
    first = load_texture(Texture(path=str(path)), "test")
    again = load_texture(Texture(path=str(path)), "test")
    assert again is first  # from the cache
    with pytest.raises(ValueError):
        first[0, 0, 0] = 0.0  # shared, so read-only
    write_png(path, 10)
    stat = path.stat()
    os.utime(path, ns=(stat.st_atime_ns, stat.st_mtime_ns + 1_000_000))
    edited = load_texture(Texture(path=str(path)), "test")
    assert edited is not first
    # sRGB 10/255 and 200/255, linearised by the IEC 61966-2-1 curve
    np.testing.assert_allclose(edited[0, 0, 0], (10 / 255) / 12.92, rtol=1e-6)
    np.testing.assert_allclose(first[0, 0, 0], ((200 / 255 + 0.055) / 1.055) ** 2.4, rtol=1e-6)


def test_the_colour_space_is_part_of_the_key(tmp_path):
    path = tmp_path / "t.png"
    write_png(path, 128)
    srgb = load_texture(Texture(path=str(path)), "test")
    raw = load_texture(Texture(path=str(path), srgb=False), "test")
    np.testing.assert_allclose(raw[0, 0, 0], 128 / 255, rtol=1e-6)
    assert srgb[0, 0, 0] < raw[0, 0, 0]


def test_pixels_are_kept_by_their_content():
    pixels = np.full((3, 5, 4), 0.5, np.float32)
    first = load_texture(Texture(pixels=pixels.copy()), "test")
    assert load_texture(Texture(pixels=pixels.copy()), "test") is first  # a fresh copy
    pixels[2, 4, 1] = 0.25
    changed = load_texture(Texture(pixels=pixels), "test")
    assert changed is not first
    np.testing.assert_allclose(changed[2, 4, 1], ((0.25 + 0.055) / 1.055) ** 2.4, rtol=1e-6)
    np.testing.assert_allclose(changed[0, 0, 0], ((0.5 + 0.055) / 1.055) ** 2.4, rtol=1e-6)
    raw = load_texture(Texture(pixels=pixels, srgb=False), "test")
    np.testing.assert_allclose(raw[2, 4, 1], 0.25, rtol=1e-6)


def test_pixels_that_are_not_finite_are_refused_each_time():
    pixels = np.full((2, 2, 3), 0.5, np.float32)
    pixels[1, 1, 2] = np.nan
    for _ in range(2):
        with pytest.raises(SceneError, match="NaN or infinity"):
            load_texture(Texture(pixels=pixels), "test")
