"""The hostile-input corpora that the command line and Blender's importer are both run
against: files a script names (`FILE_CASES`: symbolic link loops, paths too long, pipes,
folders; and scripts' own text) and texture files (`IMAGE_CASES`: decoder limits, damage of
every kind, OpenEXR's). Each case: what it is, how to make it, and what the message must
say."""

import io
import os
import struct
import tempfile
import zlib
from pathlib import Path

import numpy as np
from PIL import Image

from core.exr import write_exr

LATIN1_FOLDER = os.fsdecode(b"caf\xe9")


def loop(folder, name):
    (folder / name).symlink_to(f"{name}.2")
    (folder / f"{name}.2").symlink_to(name)


def fifo(folder, name):
    os.mkfifo(folder / name)


def dangling(folder, name):
    (folder / name).symlink_to("nowhere.obj")


def a_folder(folder, name):
    (folder / name).mkdir()


# (what the case is, the script's first line, how to make the file it names, the message)
FILE_CASES = [
    ("texture a symlink loop", "t = gr.texture('t.png', {0, 0, 0}, 1)", loop,
     "scene.lua:1: gr.texture: texture file 't.png': its path is a loop of symbolic links"),
    ("mesh a symlink loop", "m = gr.mesh('m', 'm.obj')", loop,
     "scene.lua:1: gr.mesh: mesh file 'm.obj': its path is a loop of symbolic links"),
    ("mesh path too long", "m = gr.mesh('m', '" + "d/" * 2100 + "m.obj')", None,
     "its path is too long for the file system; use a shorter one"),
    ("mesh name too long", "m = gr.mesh('m', '" + "m" * 300 + ".obj')", None,
     "its path is too long for the file system; use a shorter one"),
    ("texture a named pipe", "t = gr.texture('t.png', {0, 0, 0}, 1)", fifo,
     "scene.lua:1: gr.texture: texture file 't.png' is not a regular file"),
    ("mesh a named pipe", "m = gr.mesh('m', 'm.obj')", fifo,
     "scene.lua:1: gr.mesh: mesh file 'm.obj' is not a regular file"),
    ("mesh a link to nothing", "m = gr.mesh('m', 'm.obj')", dangling,
     "scene.lua:1: gr.mesh: mesh file 'm.obj' not found"),
    ("texture a folder", "t = gr.texture('t.png', {0, 0, 0}, 1)", a_folder,
     "scene.lua:1: gr.texture: texture file 't.png' is a folder, not a file"),
    ("mesh through a file", "m = gr.mesh('m', 'scene.lua/m.obj')", None,
     "scene.lua:1: gr.mesh: mesh file 'scene.lua/m.obj' not found"),
    ("print of bytes not UTF-8", "print('a\\255')", None,
     "scene.lua:1: print: argument 1 is not UTF-8 text"),
    ("print of a second argument not UTF-8", "x = 1\nprint('ok', 'caf\\233')", None,
     "scene.lua:2: print: argument 2 is not UTF-8 text"),
    ("__tostring giving a table", "print(setmetatable({}, {__tostring = function() "
     "return {} end}))", None, "scene.lua:1: "),
    ("string in a table not UTF-8", "gr.nh_sphere('s', {0, 0, '\\255'}, 1)", None,
     "scene.lua:1: gr.nh_sphere: a string in a table given to it is not UTF-8 text"),
]  # fmt: skip


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


def exr_bytes(channels) -> bytes:
    with tempfile.TemporaryDirectory() as folder:
        return write_exr(Path(folder) / "t.exr", channels).read_bytes()


EXR = exr_bytes({c: np.full((16, 16), 0.25, np.float32) for c in "RGB"})
NAN_EXR = exr_bytes({c: np.full((4, 4), np.nan, np.float32) for c in "RGB"})
NO_COLOUR_EXR = exr_bytes({c: np.zeros((4, 4), np.float32) for c in ("U", "V")})


DATA_WINDOW = b"dataWindow\0box2i\0" + struct.pack("<i", 16)


def exr_with(old: bytes, new: bytes) -> bytes:
    assert EXR.count(old) == 1
    return EXR.replace(old, new)


def exr_offsets(offset: int) -> bytes:
    """EXR with its first block's offset replaced (the table follows the header's end)."""
    table = EXR.index(b"\0", EXR.index(b"screenWindowWidth") + 30) + 1
    return EXR[:table] + struct.pack("<Q", offset) + EXR[table + 8 :]


def exr_garbled() -> bytes:
    """EXR with its first block's bytes (after its row and size) replaced by others."""
    table = EXR.index(b"\0", EXR.index(b"screenWindowWidth") + 30) + 1
    (first,) = struct.unpack_from("<Q", EXR, table)
    size = struct.unpack_from("<i", EXR, first + 4)[0]
    return EXR[: first + 8] + bytes(range(256))[:size] + EXR[first + 8 + size :]


TEXT_BOMB = zlib.compress(b"x" * (20 * 2**20), 9)  # 20 KiB that would be 20 MiB
DAMAGED = "cannot be decoded"
NOT_IMAGE = "is not an image Pillow reads"
# (what the case is, the file's name and bytes, what the message must say)
IMAGE_CASES = [
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
    ("OpenEXR magic alone", "t.exr", EXR[:4], "is cut short"),
    ("OpenEXR header with no end", "t.exr", EXR[:8] + b"x" * 64, "has a name in its header"),
    ("OpenEXR cut in its header", "t.exr", EXR[:60], ""),
    ("OpenEXR cut in its blocks", "t.exr", EXR[: len(EXR) - 30], ""),
    ("OpenEXR tiled", "t.exr", EXR[:4] + struct.pack("<i", 2 | 0x200) + EXR[8:],
     "is a tiled OpenEXR file"),
    ("OpenEXR version 3", "t.exr", EXR[:4] + struct.pack("<i", 3) + EXR[8:],
     "is OpenEXR version 3"),
    ("OpenEXR PIZ", "t.exr", exr_with(b"compression\0compression\0\1\0\0\0\x03",
                                      b"compression\0compression\0\1\0\0\0\x04"),
     "uses PIZ compression"),
    ("OpenEXR window of 2^31 rows", "t.exr",
     exr_with(DATA_WINDOW + struct.pack("<iiii", 0, 0, 15, 15),
              DATA_WINDOW + struct.pack("<iiii", 0, 0, 15, 2**31 - 2)),
     "textures of up to"),
    ("OpenEXR window backwards", "t.exr",
     exr_with(DATA_WINDOW + struct.pack("<iiii", 0, 0, 15, 15),
              DATA_WINDOW + struct.pack("<iiii", 0, 0, -5, 15)),
     "has a data window of"),
    ("OpenEXR block offset past its end", "t.exr", exr_offsets(10**12), "points past its end"),
    ("OpenEXR block offset into its header", "t.exr", exr_offsets(8), ""),
    ("OpenEXR garbled blocks", "t.exr", exr_garbled(), "does not inflate"),
    ("OpenEXR of NaN", "t.exr", NAN_EXR, "holds NaN or infinite values"),
    ("OpenEXR with no colour channel", "t.exr", NO_COLOUR_EXR, "none is R, G and B"),
]  # fmt: skip
