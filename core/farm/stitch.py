"""A frame's borders, rendered apart, put back together: each border's PNG (Blender's crop)
placed where its border lies, the frame written whole or not at all."""

from __future__ import annotations

import io
import os
import tempfile
from pathlib import Path

import numpy as np
from PIL import Image

from ..output_file import reason
from .jobs import Border, FarmError


def stitch(width: int, height: int, parts: dict[Border, bytes]) -> np.ndarray:
    """The frame's pixels (height, width, channels) from its borders' PNG files."""
    frame = None
    for border, data in parts.items():
        pixels = np.asarray(Image.open(io.BytesIO(data)))
        if pixels.shape[:2] != (border.height, border.width):
            raise FarmError(
                f"{border.describe()}: the worker's image is {pixels.shape[1]} x "
                f"{pixels.shape[0]} pixels, not the border's {border.width} x {border.height}"
            )
        if frame is None:
            frame = np.zeros((height, width, *pixels.shape[2:]), pixels.dtype)
        frame[border.y : border.y + border.height, border.x : border.x + border.width] = pixels
    return frame


def write_whole(path: Path, data: bytes) -> None:
    """Write beside the target, then rename: readers never see half a frame. A path that
    cannot take it is a FarmError with the system's reason."""
    temporary = None
    try:
        path.parent.mkdir(parents=True, exist_ok=True)
        handle, temporary = tempfile.mkstemp(suffix=path.suffix, prefix=".whitted-",
                                             dir=path.parent)  # fmt: skip
        with os.fdopen(handle, "wb") as out:
            out.write(data)
        umask = os.umask(0)
        os.umask(umask)
        os.chmod(temporary, 0o666 & ~umask)
        os.replace(temporary, path)
    except OSError as error:
        raise FarmError(f"-o: {path} was not written: {reason(error, path)}") from None
    finally:
        if temporary is not None and os.path.exists(temporary):
            os.unlink(temporary)


def png_bytes(pixels: np.ndarray) -> bytes:
    buffer = io.BytesIO()
    Image.fromarray(pixels).save(buffer, format="PNG")
    return buffer.getvalue()
