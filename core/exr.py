"""OpenEXR files of float channels, written with the standard library and numpy: what the
command line's `--passes` writes (Pillow neither reads nor writes EXR; `exr_read` reads
texture files).

Single-part scanline files, 32-bit float channels, ZIP compression (zlib over blocks of 16
rows, after OpenEXR's byte split and delta predictor: a tenth of the size of raw floats for
smooth passes); string attributes carry metadata such as Cryptomatte's manifest.
"""

from __future__ import annotations

import struct
import zlib
from pathlib import Path

import numpy as np

MAGIC = 20000630
FLOAT = 2  # pixel type
ZIP_COMPRESSION = 3
ROWS_PER_BLOCK = 16  # of ZIP_COMPRESSION


def _attribute(name: str, kind: str, value: bytes) -> bytes:
    return name.encode() + b"\0" + kind.encode() + b"\0" + struct.pack("<i", len(value)) + value


def _channel_list(names: list[str]) -> bytes:
    entries = b"".join(
        name.encode() + b"\0" + struct.pack("<iB3xii", FLOAT, 0, 1, 1) for name in names
    )
    return entries + b"\0"


def _compress(raw: bytes) -> bytes:
    """OpenEXR's ZIP: bytes split into even and odd halves, then deltas, then zlib."""
    data = np.frombuffer(raw, np.uint8)
    split = np.concatenate([data[0::2], data[1::2]])
    deltas = split.astype(np.int16)
    deltas[1:] = split[1:].astype(np.int16) - split[:-1].astype(np.int16) + 128
    return zlib.compress((deltas & 0xFF).astype(np.uint8).tobytes(), 6)


def write_exr(path: str | Path, channels: dict[str, np.ndarray], metadata=None) -> Path:
    """Write float (height, width) arrays, row 0 at the top, as channels named by the keys
    (e.g. "R", "G", "B", "A", or "Depth.Z"); `metadata` strings become header attributes."""
    names = sorted(channels)  # the file keeps its channels in this order
    arrays = [np.asarray(channels[n], np.float32) for n in names]
    height, width = arrays[0].shape
    if any(a.shape != (height, width) for a in arrays):
        raise ValueError("every channel of an EXR file has the image's size")
    window = struct.pack("<iiii", 0, 0, width - 1, height - 1)
    header = b"".join([
        _attribute("channels", "chlist", _channel_list(names)),
        _attribute("compression", "compression", bytes([ZIP_COMPRESSION])),
        _attribute("dataWindow", "box2i", window),
        _attribute("displayWindow", "box2i", window),
        _attribute("lineOrder", "lineOrder", b"\0"),  # increasing y
        _attribute("pixelAspectRatio", "float", struct.pack("<f", 1.0)),
        _attribute("screenWindowCenter", "v2f", struct.pack("<ff", 0.0, 0.0)),
        _attribute("screenWindowWidth", "float", struct.pack("<f", 1.0)),
        *(_attribute(k, "string", v.encode()) for k, v in sorted((metadata or {}).items())),
    ])  # fmt: skip
    # Per row, each channel's values in turn; per block of rows, those rows one after another
    rows = np.stack(arrays, axis=1).astype("<f4")  # (height, channels, width)
    blocks = []
    for y in range(0, height, ROWS_PER_BLOCK):
        raw = rows[y : y + ROWS_PER_BLOCK].tobytes()
        data = _compress(raw)
        if len(data) >= len(raw):  # readers take a block no smaller than raw as raw
            data = raw
        blocks.append(struct.pack("<ii", y, len(data)) + data)
    start = 8 + len(header) + 1 + 8 * len(blocks)
    offsets, position = [], start
    for block in blocks:
        offsets.append(position)
        position += len(block)
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    with open(path, "wb") as out:
        out.write(struct.pack("<ii", MAGIC, 2))
        out.write(header + b"\0")
        out.write(struct.pack(f"<{len(offsets)}Q", *offsets))
        out.write(b"".join(blocks))
    return path
