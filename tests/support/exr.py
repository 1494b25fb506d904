"""A reader of scanline OpenEXR files, for the tests: written from the file format's
specification, apart from `core.exr` (the writer it checks), and itself checked on the
files Blender's own OpenEXR library writes. Uncompressed, ZIPS and ZIP blocks; half, float
and uint channels."""

from __future__ import annotations

import struct
import zlib
from pathlib import Path

import numpy as np

ROWS = {0: 1, 2: 1, 3: 16}  # rows per block: NONE, ZIPS, ZIP
DTYPES = {0: "<u4", 1: "<f2", 2: "<f4"}


def _cstring(data: bytes, at: int) -> tuple[str, int]:
    end = data.index(b"\0", at)
    return data[at:end].decode(), end + 1


def _channels(value: bytes) -> list[tuple[str, int]]:
    found, at = [], 0
    while value[at] != 0:
        name, at = _cstring(value, at)
        (pixel_type,) = struct.unpack_from("<i", value, at)
        found.append((name, pixel_type))
        at += 16
    return found


def _unzip(data: bytes, size: int) -> bytes:
    deltas = np.frombuffer(zlib.decompress(data), np.uint8).astype(np.int64)
    # undo the predictor: each byte is the previous one plus its delta - 128
    values = (np.cumsum(np.concatenate([deltas[:1], deltas[1:] - 128])) & 0xFF).astype(np.uint8)
    half = (size + 1) // 2
    out = np.empty(size, np.uint8)
    out[0::2], out[1::2] = values[:half], values[half:]
    return out.tobytes()


def _header(data: bytes, at: int) -> tuple[dict, dict, int]:
    """(attributes, string attributes, the offset after the header's closing null)."""
    attributes, strings = {}, {}
    while data[at] != 0:
        name, at = _cstring(data, at)
        kind, at = _cstring(data, at)
        (size,) = struct.unpack_from("<i", data, at)
        value = data[at + 4 : at + 4 + size]
        at += 4 + size
        attributes[name] = value
        if kind == "string":
            strings[name] = value.decode()
    return attributes, strings, at + 1


def read_exr(path: str | Path) -> tuple[dict[str, np.ndarray], dict[str, str]]:
    """(channel name -> float (height, width) array with row 0 at the top, the string
    attributes of the header). A multi-part file's channels are gathered from all its parts
    (Blender 5 writes a part per pass, its channels named in full, "ViewLayer.Depth.Z"), and
    the string attributes of all its parts merged."""
    data = Path(path).read_bytes()
    magic, version = struct.unpack_from("<ii", data, 0)
    assert magic == 20000630 and version & 0xFF == 2 and not version & 0x200, "scanline only"
    multipart = bool(version & 0x1000)
    at, headers = 8, []
    while True:
        attributes, strings, at = _header(data, at)
        headers.append((attributes, strings))
        if not multipart or data[at] == 0:
            break
    at += 1 if multipart else 0
    images, metadata = {}, {}
    tables = []
    for attributes, strings in headers:
        metadata.update(strings)
        x0, y0, x1, y1 = struct.unpack("<iiii", attributes["dataWindow"])
        rows = ROWS[attributes["compression"][0]]
        blocks = -(-(y1 - y0 + 1) // rows)
        tables.append(struct.unpack_from(f"<{blocks}Q", data, at))
        at += 8 * blocks
    for (attributes, _), offsets in zip(headers, tables, strict=True):
        images.update(_part_pixels(data, attributes, offsets, multipart))
    return images, metadata


def _part_pixels(data: bytes, attributes: dict, offsets, multipart: bool) -> dict:
    channels = sorted(_channels(attributes["channels"]))
    x0, y0, x1, y1 = struct.unpack("<iiii", attributes["dataWindow"])
    width, height = x1 - x0 + 1, y1 - y0 + 1
    compression = attributes["compression"][0]
    rows = ROWS[compression]
    images = {name: np.zeros((height, width)) for name, _ in channels}
    row_bytes = sum(width * np.dtype(DTYPES[t]).itemsize for _, t in channels)
    for offset in offsets:
        offset += 4 if multipart else 0  # the part's number
        y, size = struct.unpack_from("<ii", data, offset)
        block = data[offset + 8 : offset + 8 + size]
        count = min(rows, y1 + 1 - y)
        if compression != 0 and size < row_bytes * count:
            block = _unzip(block, row_bytes * count)
        position = 0
        for r in range(count):
            for name, pixel_type in channels:
                dtype = np.dtype(DTYPES[pixel_type])
                values = np.frombuffer(block, dtype, width, position)
                images[name][y - y0 + r] = values
                position += width * dtype.itemsize
    return images
