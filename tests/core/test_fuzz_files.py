"""Fuzzing the files a scene reads: texture images (random valid PNG, JPEG, TIFF, BMP, GIF
and OpenEXR files of every mode, then broken: bytes flipped, cut short, chunks of random kind
and size put in, header fields set to edge values; bare OpenEXR headers) and OBJ meshes
(lines of every statement with edge numbers and indices, and random bytes). Each must read
to finite values of the right shape or fail with the reader's own error (`ImageFileError`,
`ObjError`), whose message the caller puts at the script's line: never another exception,
and in bounded time.

`make test` runs a fixed-seed sample; `make fuzz` runs thousands with a random seed.
"""

import io
import struct
import tempfile
import time
import zlib
from pathlib import Path

import numpy as np
from hypothesis import given
from hypothesis import strategies as st
from PIL import Image

from core.exr import write_exr
from core.obj_file import ObjError, parse_obj
from core.textures import MAX_TEXTURE_PIXELS, ImageFileError, read_rgb
from tests.support.fuzz_scenes import FUZZ

EXAMPLE_SECONDS = 20  # one file read, however hostile (a 64 M pixel bomb decodes in ~5)
FORMATS = {
    "PNG": ("1", "L", "LA", "P", "RGB", "RGBA", "I;16"),
    "TIFF": ("1", "L", "RGB", "RGBA", "CMYK", "I;16", "I", "F"),
    "JPEG": ("L", "RGB", "CMYK"),
    "BMP": ("1", "L", "P", "RGB"),
    "GIF": ("L", "P"),
}
EDGE_INTEGERS = [0, 1, 2**15, 2**16 - 1, 2**31 - 1, 2**31, 2**32 - 1]


def png_chunk(kind: bytes, data: bytes) -> bytes:
    crc = zlib.crc32(kind + data) & 0xFFFFFFFF
    return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", crc)


@st.composite
def valid_images(draw) -> bytes:
    kind = draw(st.sampled_from([*sorted(FORMATS), "EXR"]))
    width, height = draw(st.integers(1, 24)), draw(st.integers(1, 24))
    seed = draw(st.integers(0, 2**32 - 1))
    rng = np.random.default_rng(seed)
    if kind == "EXR":  # Whitted's own writer: float channels, ZIP blocks
        names = draw(st.sampled_from([("R", "G", "B"), ("A", "B", "G", "R"), ("Y",), ("Z",)]))
        with tempfile.TemporaryDirectory() as folder:
            channels = {n: rng.random((height, width)).astype(np.float32) for n in names}
            return write_exr(Path(folder) / "t.exr", channels).read_bytes()
    mode = draw(st.sampled_from(FORMATS[kind]))
    image = Image.frombytes("RGB", (width, height), rng.integers(0, 256, width * height * 3,
                                                                 np.uint8).tobytes())  # fmt: skip
    if mode in ("I;16", "I", "F"):
        values = rng.integers(0, 65536, (height, width))
        image = Image.fromarray(values.astype({"I;16": np.uint16, "I": np.int32,
                                               "F": np.float32}[mode]))  # fmt: skip
    else:
        image = image.convert(mode)
    out = io.BytesIO()
    image.save(out, kind)
    return out.getvalue()


@st.composite
def broken_images(draw) -> bytes:
    data = bytearray(draw(valid_images()))
    for _ in range(draw(st.integers(1, 4))):
        how = draw(st.integers(0, 4))
        if how == 0 and data:  # bytes flipped
            at = draw(st.integers(0, len(data) - 1))
            data[at] ^= draw(st.integers(1, 255))
        elif how == 1:  # cut short
            data = data[: draw(st.integers(0, len(data)))]
        elif how == 2:  # a chunk of any kind put in after the header (PNG's shape)
            kind = draw(st.sampled_from([b"zTXt", b"iTXt", b"tEXt", b"iCCP", b"IDAT", b"IHDR",
                                         b"PLTE", b"tRNS", b"eXIf", b"fdAT", b"abcd"]))  # fmt: skip
            body = draw(st.binary(max_size=64))
            if draw(st.booleans()):
                body += zlib.compress(b"\0" * draw(st.integers(0, 8 * 2**20)))
            at = min(33, len(data))
            data[at:at] = png_chunk(kind, body)
        elif how == 3 and len(data) >= 24:  # a header's field set to an edge value
            at = draw(st.integers(0, min(len(data), 64) - 4))
            value = draw(st.sampled_from(EDGE_INTEGERS))
            data[at : at + 4] = struct.pack(draw(st.sampled_from([">I", "<I"])), value)
        else:  # random bytes appended or put in
            at = draw(st.integers(0, len(data)))
            data[at:at] = draw(st.binary(max_size=32))
    return bytes(data)


exr_headers = st.binary(max_size=200).map(lambda b: b"\x76\x2f\x31\x01\x02\0\0\0" + b)
image_files = st.one_of(valid_images(), broken_images(), exr_headers, st.binary(max_size=64))


@FUZZ
@given(data=image_files, suffix=st.sampled_from([".png", ".jpg", ".tif", ".bmp", ".gif",
                                                 ".exr"]))  # fmt: skip
def test_random_image_files_read_finitely_or_fail_clearly(tmp_path_factory, data, suffix):
    path = tmp_path_factory.mktemp("image") / f"texture{suffix}"
    path.write_bytes(data)
    start = time.monotonic()
    try:
        rgb = read_rgb(path)
    except ImageFileError as problem:
        assert str(problem) and "\n" not in str(problem)
    else:
        assert rgb.ndim == 3 and rgb.shape[2] == 3
        assert rgb.shape[0] * rgb.shape[1] <= MAX_TEXTURE_PIXELS
        assert np.all(np.isfinite(rgb))
    assert time.monotonic() - start < EXAMPLE_SECONDS


EDGE_NUMBERS = ["0", "-0", "1", "-1", "0.5", "1e308", "-1e308", "1e-320", "nan", "inf",
                "-inf", "1e999", "0x10", "1,5", "", "++1", "1e", str(2**63), str(-(2**64)),
                "९"]  # fmt: skip
EDGE_INDICES = ["1", "2", "3", "-1", "-3", "0", "4", str(2**31), str(2**64), "-99999999999",
                "1.5", "a", "", "1/", "1//", "1/1/1/1", "/1", "//"]  # fmt: skip
numbers = st.one_of(st.sampled_from(EDGE_NUMBERS), st.floats(allow_nan=True).map(repr),
                    st.integers(-(10**30), 10**30).map(str))  # fmt: skip
corners = st.one_of(
    st.sampled_from(EDGE_INDICES),
    st.tuples(st.sampled_from(EDGE_INDICES), st.sampled_from(["", "1", "-1", "9"]),
              st.sampled_from(["", "1", "-1", "9"])).map("/".join),
)  # fmt: skip


@st.composite
def obj_lines(draw) -> str:
    kind = draw(st.integers(0, 9))
    if kind <= 2:
        return "v " + " ".join(draw(st.lists(numbers, min_size=0, max_size=5)))
    if kind == 3:
        return "vt " + " ".join(draw(st.lists(numbers, max_size=4)))
    if kind == 4:
        return "vn " + " ".join(draw(st.lists(numbers, max_size=4)))
    if kind <= 7:
        return "f " + " ".join(draw(st.lists(corners, max_size=6)))
    if kind == 8:
        return draw(st.sampled_from(["o x", "g", "s off", "usemtl m", "mtllib a.mtl", "# c",
                                     "l 1 2", "p 1", "\\", "f"]))  # fmt: skip
    return draw(st.binary(max_size=20)).decode("latin-1")


@st.composite
def obj_files(draw) -> bytes:
    start = ["v 0 0 0", "v 1 0 0", "v 0 1 0", "f 1 2 3"] if draw(st.booleans()) else []
    lines = start + draw(st.lists(obj_lines(), max_size=20))
    ending = draw(st.sampled_from(["\n", "\r\n", "\r", ""]))
    return ending.join(lines).encode("latin-1", "replace") + draw(st.binary(max_size=4))


@FUZZ
@given(data=obj_files())
def test_random_obj_files_read_finitely_or_fail_clearly(data):
    start = time.monotonic()
    try:
        mesh = parse_obj(data, "m", "mesh.obj")
    except ObjError as problem:
        assert str(problem).startswith("mesh.obj")
    else:
        for array in (mesh.vertices, mesh.vertex_normals, mesh.corner_normals, mesh.corner_uvs):
            if array is not None:
                assert np.all(np.isfinite(array))
        faces = np.asarray(mesh.triangles)
        assert faces.ndim == 2 and faces.shape[1] == 3
        assert faces.min() >= 0 and faces.max() < len(mesh.vertices)
    assert time.monotonic() - start < EXAMPLE_SECONDS
