"""Reading OpenEXR images as texture colours, with the standard library and numpy (Pillow
reads no EXR): single-part scanline files, uncompressed, RLE, ZIPS or ZIP; half, float and
uint channels; R, G, B (a layer's too, "Layer.R") or one grey channel (Y, or the only one).

Every field is read as hostile: sizes, offsets and counts are checked against the file
before they are used, and a block is inflated to no more than its rows hold, so a broken or
crafted file fails with `ExrError` saying what is wrong, never reads past its end or fills
the memory.
"""

from __future__ import annotations

import struct
import zlib

import numpy as np

MAGIC = 20000630
_TILED, _LONG_NAMES, _DEEP, _MULTIPART = 0x200, 0x400, 0x800, 0x1000
_ROWS = {0: 1, 1: 1, 2: 1, 3: 16}  # rows a block: NONE, RLE, ZIPS, ZIP
_COMPRESSIONS = ("none", "RLE", "ZIPS", "ZIP", "PIZ", "PXR24", "B44", "B44A", "DWAA", "DWAB")
_TYPES = {0: ("<u4", 4), 1: ("<f2", 2), 2: ("<f4", 4)}  # uint, half, float
_MAX_HEADER = 1 << 20


class ExrError(ValueError):
    """Why an OpenEXR file cannot be read, as the end of a sentence naming the file."""


def read_exr_rgb(data: bytes, too_large) -> np.ndarray:
    """(height, width, 3) float64 RGB, row 0 at the top, of the OpenEXR file's bytes.
    too_large((width, height)) says why an image of that size is refused, or None."""
    if len(data) < 4 or struct.unpack_from("<i", data, 0)[0] != MAGIC:
        raise ExrError("is not an OpenEXR file (its first bytes are not OpenEXR's)")
    if len(data) < 8:
        raise ExrError("is cut short before its header")
    (version,) = struct.unpack_from("<i", data, 4)
    if version & 0xFF != 2:
        raise ExrError(f"is OpenEXR version {version & 0xFF}; version 2 files are read")
    if version & (_TILED | _DEEP | _MULTIPART):
        kind = "tiled" if version & _TILED else "deep" if version & _DEEP else "multi-part"
        raise ExrError(f"is a {kind} OpenEXR file; save it as a single-part scanline image")
    header = _header(data)
    channels = _channel_list(header.get("channels"))
    compression = _byte(header, "compression")
    if compression not in _ROWS:
        name = _COMPRESSIONS[compression] if compression < len(_COMPRESSIONS) else compression
        raise ExrError(f"uses {name} compression; save it with ZIP, ZIPS, RLE or none")
    window = header.get("dataWindow")
    if window is None or len(window) != 16:
        raise ExrError("has no dataWindow attribute; it is damaged")
    x0, y0, x1, y1 = struct.unpack("<iiii", window)
    width, height = x1 - x0 + 1, y1 - y0 + 1
    if width < 1 or height < 1:
        raise ExrError(f"has a data window of {width} x {height} pixels; it is damaged")
    if problem := too_large((width, height)):
        raise ExrError(problem)
    picked = _colour_channels([name for name, _ in channels])
    planes = _planes(data, header["_end"], channels, compression, width, height, y0)
    values = [planes[name] for name in picked]
    return np.stack(values if len(values) == 3 else values * 3, axis=2)


def _header(data: bytes) -> dict:
    """The header's attributes by name (bytes), and where it ends (`_end`)."""
    attributes, at = {}, 8
    while True:
        if at >= min(len(data), _MAX_HEADER):
            raise ExrError("has a header with no end; it is damaged or cut short")
        if data[at] == 0:
            attributes["_end"] = at + 1
            return attributes
        name, at = _text(data, at)
        _, at = _text(data, at)
        if at + 4 > len(data):
            raise ExrError("is cut short in its header")
        (size,) = struct.unpack_from("<i", data, at)
        if not 0 <= size <= len(data) - at - 4:
            raise ExrError(f"has an attribute '{name}' of {size} bytes past its end")
        attributes[name] = data[at + 4 : at + 4 + size]
        at += 4 + size


def _text(data: bytes, at: int) -> tuple[str, int]:
    end = data.find(b"\0", at, at + 256)
    if end < 0:
        raise ExrError("has a name in its header longer than any OpenEXR name")
    return data[at:end].decode("latin-1"), end + 1


def _byte(header: dict, name: str) -> int:
    value = header.get(name)
    if value is None or len(value) != 1:
        raise ExrError(f"has no {name} attribute; it is damaged")
    return value[0]


def _channel_list(value: bytes | None) -> list[tuple[str, int]]:
    """(name, pixel type) of each channel, in the file's (alphabetical) order."""
    if not value:
        raise ExrError("has no channels attribute; it is damaged")
    found, at = [], 0
    while at < len(value) and value[at] != 0:
        name, at = _text(value, at)
        if at + 16 > len(value):
            raise ExrError("has a channel list cut short; it is damaged")
        pixel_type, _, x_sampling, y_sampling = struct.unpack_from("<iB3xii", value, at)
        if pixel_type not in _TYPES:
            raise ExrError(f"has channel '{name}' of unknown pixel type {pixel_type}")
        if (x_sampling, y_sampling) != (1, 1):
            raise ExrError(f"has channel '{name}' subsampled; save it at full resolution")
        found.append((name, pixel_type))
        at += 16
    if not found:
        raise ExrError("has no channels")
    return found


def _colour_channels(names: list[str]) -> list[str]:
    """R, G and B (of the first layer that has all three), else one grey channel."""
    for prefix in sorted({n.rpartition(".")[0] for n in names}):
        dot = prefix + "." if prefix else ""
        if all(f"{dot}{c}" in names for c in "RGB"):
            return [f"{dot}{c}" for c in "RGB"]
    for grey in ("Y", "R", "L", "Z"):
        if grey in names:
            return [grey]
    if len(names) == 1:
        return names
    raise ExrError(
        f"has channels {', '.join(names[:8])}: none is R, G and B or a grey Y; name them so"
    )


def _planes(data, start, channels, compression, width, height, y0) -> dict[str, np.ndarray]:
    """Each channel's (height, width) float64 values, read block by block."""
    rows = _ROWS[compression]
    blocks = -(-height // rows)
    if start + 8 * blocks > len(data):
        raise ExrError("is cut short in its table of blocks")
    offsets = np.frombuffer(data, "<u8", blocks, start)
    bytes_per_row = sum(width * _TYPES[kind][1] for _, kind in channels)
    planes = {name: np.empty((height, width)) for name, _ in channels}
    for offset in offsets:
        if not offset <= len(data) - 8:
            raise ExrError("points past its end for a block of rows; it is damaged")
        first, size = struct.unpack_from("<ii", data, int(offset))
        row = first - y0
        if not (0 <= row < height and row % rows == 0 and 0 <= size <= len(data) - offset - 8):
            raise ExrError(f"has a block of rows at y {first} of {size} bytes that does not fit")
        count = min(rows, height - row)
        raw = _unpacked(data[int(offset) + 8 : int(offset) + 8 + size], compression,
                        count * bytes_per_row)  # fmt: skip
        at = 0
        for line in range(row, row + count):
            for name, kind in channels:
                dtype, size_of = _TYPES[kind]
                planes[name][line] = np.frombuffer(raw, dtype, width, at)
                at += width * size_of
    return planes


def _unpacked(block: bytes, compression: int, expected: int) -> bytes:
    """A block's bytes as stored raw; a compressed block no smaller than raw is raw."""
    if compression == 0 or len(block) == expected:
        if len(block) != expected:
            raise ExrError(f"has a block of {len(block)} bytes where its rows hold {expected}")
        return block
    if compression == 1:
        predicted = _run_lengths(block, expected)
    else:
        inflater = zlib.decompressobj()
        try:
            predicted = inflater.decompress(block, expected)
        except zlib.error as error:
            raise ExrError(f"has a block that does not inflate ({error})") from None
        if len(predicted) != expected or inflater.unconsumed_tail:
            raise ExrError(f"has a block that inflates to other than its {expected} bytes")
    deltas = np.frombuffer(predicted, np.uint8).astype(np.int64)
    values = (np.cumsum(np.concatenate([deltas[:1], deltas[1:] - 128])) & 0xFF).astype(np.uint8)
    half = (expected + 1) // 2
    out = np.empty(expected, np.uint8)
    out[0::2], out[1::2] = values[:half], values[half:]
    return out.tobytes()


def _run_lengths(block: bytes, expected: int) -> bytes:
    """OpenEXR's RLE: a signed count, then that many literal bytes (negative) or one byte
    repeated count + 1 times."""
    out, at = bytearray(), 0
    while at < len(block) and len(out) < expected:
        count = struct.unpack_from("b", block, at)[0]
        at += 1
        if count < 0:
            out += block[at : at - count]
            at -= count
        elif at < len(block):
            out += block[at : at + 1] * (count + 1)
            at += 1
    if len(out) != expected:
        raise ExrError(f"has an RLE block that unpacks to other than its {expected} bytes")
    return bytes(out)
