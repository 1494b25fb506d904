"""Texture files are read at their true values in every mode Pillow opens: the values are
known here because the test writes them (8-bit, 16-bit, grey, palette, alpha, CMYK, float).
Before, Pillow's convert("RGB") clipped a 16-bit grey PNG to all white and a float TIFF of
0.5 to black."""

import struct
import zlib

import numpy as np
import pytest
from PIL import Image

from core.textures import ImageFileError, read_rgb

# A 2 x 3 ramp of levels in 0..1, and each file's expected RGB
LEVELS = np.array([[0.0, 0.2, 0.4], [0.6, 0.8, 1.0]])


def grey_rgb(levels):
    return np.repeat(levels[:, :, None], 3, axis=2)


def png_chunk(kind: bytes, data: bytes) -> bytes:
    crc = zlib.crc32(kind + data) & 0xFFFFFFFF
    return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", crc)


def png_16bit_rgb(rgb16: np.ndarray) -> bytes:
    """A 16-bit RGB PNG by hand (Pillow writes none)."""
    height, width, _ = rgb16.shape
    rows = b"".join(b"\0" + rgb16[y].astype(">u2").tobytes() for y in range(height))
    header = struct.pack(">IIBBBBB", width, height, 16, 2, 0, 0, 0)
    body = png_chunk(b"IHDR", header) + png_chunk(b"IDAT", zlib.compress(rows))
    return b"\x89PNG\r\n\x1a\n" + body + png_chunk(b"IEND", b"")


def cmyk(inks: np.ndarray) -> Image.Image:
    return Image.frombytes("CMYK", inks.shape[1::-1], inks.tobytes())


def save(image: Image.Image, path, **options):
    image.save(path, **options)
    return path


def cases(tmp_path):
    """(name, file, expected RGB, tolerance)"""
    grey8 = np.round(LEVELS * 255).astype(np.uint8)
    grey16 = np.round(LEVELS * 65535).astype(np.uint16)
    colour = np.stack([LEVELS, 1 - LEVELS, np.full_like(LEVELS, 0.4)], axis=2)
    colour8 = np.round(colour * 255).astype(np.uint8)
    made = []

    def add(name, image, suffix, expected, tolerance=1e-9, **options):
        made.append((name, save(image, tmp_path / f"{name}.{suffix}", **options), expected,
                     tolerance))  # fmt: skip

    add("grey 8-bit png", Image.fromarray(grey8), "png", grey8 / 255.0)
    add("grey 16-bit png", Image.fromarray(grey16), "png", grey16 / 65535.0)
    add("grey 16-bit tiff", Image.fromarray(grey16), "tiff", grey16 / 65535.0)
    add("grey 32-bit int tiff", Image.fromarray(grey16.astype(np.int32)), "tiff",
        grey16 / 65535.0)  # fmt: skip
    add("float tiff", Image.fromarray(LEVELS.astype(np.float32) * 3), "tiff",
        grey_rgb(LEVELS.astype(np.float32) * 3), 1e-7)  # fmt: skip
    add("one bit png", Image.fromarray(grey8 > 127), "png", (grey8 > 127) * 1.0)
    add("grey alpha png", Image.fromarray(np.stack([grey8, 255 - grey8], 2)), "png",
        grey8 / 255.0)  # fmt: skip
    add("rgb png", Image.fromarray(colour8), "png", colour8 / 255.0)
    add("rgba png", Image.fromarray(np.dstack([colour8, grey8])), "png",
        colour8 / 255.0)  # fmt: skip
    add("rgb tiff", Image.fromarray(colour8), "tiff", colour8 / 255.0)
    add("rgb bmp", Image.fromarray(colour8), "bmp", colour8 / 255.0)
    palette = Image.fromarray(colour8).quantize(colors=6, method=Image.Quantize.FASTOCTREE)
    add("palette png", palette, "png", colour8 / 255.0)
    add("palette gif", palette, "gif", colour8 / 255.0)
    transparent = palette.copy()
    transparent.info["transparency"] = 0
    add("palette with transparency png", transparent, "png", colour8 / 255.0)
    # CMYK's pure inks: cyan, magenta, yellow, black, none, and cyan over yellow (green)
    inks = np.array([[[255, 0, 0, 0], [0, 255, 0, 0], [0, 0, 255, 0]],
                     [[0, 0, 0, 255], [0, 0, 0, 0], [255, 0, 255, 0]]], np.uint8)  # fmt: skip
    rgb_of_inks = np.array([[[0, 1, 1], [1, 0, 1], [1, 1, 0]], [[0, 0, 0], [1, 1, 1], [0, 1, 0]]])
    add("cmyk tiff", cmyk(inks), "tiff", rgb_of_inks * 1.0)
    flat = np.full((16, 16, 3), (200, 100, 50), np.uint8)  # JPEG is lossy: one flat colour
    add("rgb jpeg", Image.fromarray(flat), "jpg", flat / 255.0, 2.5 / 255, quality=95)
    add("grey jpeg", Image.fromarray(flat[:, :, 0]), "jpg", grey_rgb(flat[:, :, 0] / 255.0),
        1.5 / 255, quality=95)  # fmt: skip
    add("cmyk jpeg", cmyk(np.full((16, 16, 4), (0, 255, 255, 0), np.uint8)),
        "jpg", np.full((16, 16, 3), (1.0, 0.0, 0.0)), 3 / 255, quality=95)  # fmt: skip
    rgb16 = np.round(colour * 65535).astype(np.uint16)
    (tmp_path / "rgb16.png").write_bytes(png_16bit_rgb(rgb16))
    # Pillow reads 16-bit RGB as 8-bit: true to 8 bits, not clipped
    made.append(("rgb 16-bit png", tmp_path / "rgb16.png", rgb16 / 65535.0, 1 / 255))
    return made


def test_every_mode_is_read_at_its_true_values(tmp_path):
    checked = []
    for name, path, expected, tolerance in cases(tmp_path):
        expected = expected if expected.ndim == 3 else grey_rgb(expected)
        got = read_rgb(path)
        assert got.shape == expected.shape, name
        assert np.max(np.abs(got - expected)) <= tolerance, (name, got, expected)
        checked.append(Image.open(path).mode)
    # the modes Pillow opened these files in: every family the issue names
    assert {"1", "L", "LA", "I;16", "I", "F", "P", "RGB", "RGBA", "CMYK"} <= set(checked)


def test_a_float_texture_with_nan_is_refused_by_name(tmp_path):
    values = np.array([[0.5, np.nan]], np.float32)
    Image.fromarray(values).save(tmp_path / "nan.tiff")
    with pytest.raises(ImageFileError, match="NaN or infinite values"):
        read_rgb(tmp_path / "nan.tiff")


def test_32_bit_samples_beyond_16_bits_are_refused_not_clipped(tmp_path):
    Image.fromarray(np.array([[70000]], np.int32)).save(tmp_path / "big.tiff")
    with pytest.raises(ImageFileError, match="beyond 16 bits"):
        read_rgb(tmp_path / "big.tiff")
