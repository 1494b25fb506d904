"""Hostile texture files, each named by a script run as a user runs it (`python -m core
render`): the script's line names the file and why it cannot be read (decoder limits
included), exit 1, no traceback, nothing written. Before, a PNG whose text chunk was too
large to decompress killed the process running the script ("this is Whitted's fault")."""

import io
import struct
import subprocess
import sys
import time
import zlib

import numpy as np
import pytest
from PIL import Image

from tests.core.cs488.test_hostile_scripts import NORMAL, run


def chunk(kind: bytes, data: bytes) -> bytes:
    crc = zlib.crc32(kind + data) & 0xFFFFFFFF
    return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", crc)


def encoded(image: Image.Image, kind: str) -> bytes:
    out = io.BytesIO()
    image.save(out, kind)
    return out.getvalue()


GREY = Image.new("L", (16, 16), 100)
PNG = encoded(GREY, "PNG")
NOISE = encoded(Image.fromarray(np.random.default_rng(1).integers(0, 256, (64, 64), np.uint8)),
                "PNG")  # fmt: skip
JPEG = encoded(Image.new("RGB", (16, 16), (200, 100, 50)), "JPEG")
TIFF = encoded(GREY, "TIFF")
HEADER_END = 8 + 25  # the signature and the IHDR chunk


def with_chunk(extra: bytes) -> bytes:
    return PNG[:HEADER_END] + extra + PNG[HEADER_END:]


def bad_crc(png: bytes) -> bytes:
    at = png.index(b"IDAT") - 4
    (size,) = struct.unpack_from(">I", png, at)
    crc_at = at + 8 + size
    return png[:crc_at] + bytes(b ^ 0xFF for b in png[crc_at : crc_at + 4]) + png[crc_at + 4 :]


def ihdr(width: int, height: int, depth=8, colour=0) -> bytes:
    header = struct.pack(">IIBBBBB", width, height, depth, colour, 0, 0, 0)
    rows = zlib.compress(b"\0" * (min(width, 64) + 1) * min(height, 64))
    body = chunk(b"IHDR", header) + chunk(b"IDAT", rows) + chunk(b"IEND", b"")
    return b"\x89PNG\r\n\x1a\n" + body


def float_tiff(values) -> bytes:
    return encoded(Image.fromarray(np.array(values, np.float32)), "TIFF")


TEXT_BOMB = zlib.compress(b"x" * (20 * 2**20), 9)  # 20 KiB that would be 20 MiB
DAMAGED = "cannot be decoded"
NOT_IMAGE = "is not an image Pillow reads"
# (what the case is, the file's name and bytes, what the message must say)
CASES = [
    ("zTXt chunk of 20 MiB", "t.png", with_chunk(chunk(b"zTXt", b"Comment\0\0" + TEXT_BOMB)),
     "holds a text chunk (metadata) larger than Pillow decompresses"),
    ("iTXt chunk of 20 MiB", "t.png",
     with_chunk(chunk(b"iTXt", b"Comment\0\1\0\0\0" + TEXT_BOMB)),
     "holds a text chunk (metadata) larger than Pillow decompresses"),
    ("iCCP profile of 20 MiB", "t.png", with_chunk(chunk(b"iCCP", b"icc\0\0" + TEXT_BOMB)),
     ""),
    ("truncated in its pixels", "t.png", NOISE[: len(NOISE) // 2], DAMAGED),
    ("a pixel chunk's checksum wrong", "t.png", bad_crc(PNG), DAMAGED),
    ("the signature alone", "t.png", PNG[:8], NOT_IMAGE),
    ("no bytes at all", "t.png", b"", NOT_IMAGE),
    ("text named .png", "t.png", b"this is not a picture\n", NOT_IMAGE),
    ("width 0", "t.png", ihdr(0, 16), ""),
    ("bit depth 3", "t.png", ihdr(16, 16, depth=3), ""),
    ("colour type 7", "t.png", ihdr(16, 16, colour=7), ""),
    ("2^31 x 2^31 pixels", "t.png", ihdr(2**31 - 1, 2**31 - 1), "has more pixels than any"),
    ("JPEG cut after its header", "t.jpg", JPEG[:200], ""),
    ("JPEG's markers garbled", "t.jpg", JPEG[:2] + bytes(range(256)) * 2, ""),
    ("TIFF pointing past its end", "t.tiff", TIFF[:4] + struct.pack("<I", 10**9) + TIFF[8:], ""),
    ("TIFF cut in its pixels", "t.tiff", TIFF[:-100], ""),
    ("GIF header alone", "t.gif", b"GIF89a" + struct.pack("<HH", 16, 16) + b"\0\0\0", ""),
    ("BMP of negative size", "t.bmp",
     b"BM" + struct.pack("<IHHI", 70, 0, 0, 54) + struct.pack("<IiiHHIIiiII", 40, -5, -5, 1, 24,
                                                              0, 0, 0, 0, 0, 0), ""),
    ("float TIFF with NaN", "t.tiff", float_tiff([[0.5, np.nan]]), "holds NaN or infinite values"),
    ("float TIFF with infinity", "t.tiff", float_tiff([[np.inf]]), "holds NaN or infinite values"),
    ("an OpenEXR file", "t.exr", b"\x76\x2f\x31\x01\x02\0\0\0" + b"\0" * 64,
     "is an OpenEXR image, which the command line does not read"),
]  # fmt: skip


@pytest.mark.parametrize("case, name, data, says", CASES, ids=[c[0] for c in CASES])
def test_a_hostile_texture_is_named_at_the_scripts_line(tmp_path, case, name, data, says):
    (tmp_path / name).write_bytes(data)
    (tmp_path / "scene.lua").write_text(f"t = gr.texture('{name}', {{0, 0, 0}}, 1)\n" + NORMAL)
    before = sorted(p.name for p in tmp_path.iterdir())
    start = time.monotonic()
    result = run(tmp_path, tmp_path / "scene.lua")
    assert time.monotonic() - start < 60
    assert result.returncode == 1, result.stdout + result.stderr
    assert "Traceback" not in result.stderr and "Whitted's fault" not in result.stderr, (
        result.stderr
    )
    last = result.stderr.strip().splitlines()[-1]
    assert last.startswith(f"error: scene.lua:1: gr.texture: texture file '{name}' "), last
    assert says in last, last
    assert sorted(p.name for p in tmp_path.iterdir()) == before


def test_a_16_bit_grey_texture_renders_as_its_8_bit_twin(tmp_path):
    """End to end: a 16-bit grey PNG of 0.25 renders as an 8-bit PNG of 64/255 does (it
    rendered all white)."""
    Image.fromarray(np.full((8, 8), round(0.25 * 65535), np.uint16)).save(tmp_path / "a.png")
    Image.fromarray(np.full((8, 8), 64, np.uint8)).save(tmp_path / "b.png")
    pictures = []
    for texture in ("a.png", "b.png"):
        scene = f"t = gr.texture('{texture}', {{0, 0, 0}}, 1)\n" + NORMAL.replace(
            "r:add_child(gr.sphere('s'))", "s = gr.sphere('s')\ns:set_texture(t)\nr:add_child(s)"
        ).replace("{0, 0, 0}, {})", "{1, 1, 1}, {})")
        (tmp_path / "scene.lua").write_text(scene)
        assert run(tmp_path, tmp_path / "scene.lua").returncode == 0
        pictures.append(np.asarray(Image.open(tmp_path / "o.png"), np.int16))
    assert pictures[1][4, 4, 0] > 40  # the sphere is lit by the ambient term: not black
    assert np.max(np.abs(pictures[0] - pictures[1])) <= 1


def test_the_message_names_a_file_by_the_scripts_name_of_it(tmp_path):
    (tmp_path / "sub").mkdir()
    (tmp_path / "sub" / "t.png").write_bytes(b"")
    (tmp_path / "scene.lua").write_text("t = gr.texture('sub/t.png', {0, 0, 0}, 1)\n")
    result = subprocess.run(
        [sys.executable, "-m", "core", "render", "scene.lua"],
        cwd=tmp_path, capture_output=True, text=True, timeout=120,
    )  # fmt: skip
    assert "texture file 'sub/t.png' is not an image" in result.stderr
