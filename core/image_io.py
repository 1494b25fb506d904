"""Writing rendered images to disk with Pillow."""

from pathlib import Path

import numpy as np
from PIL import Image


def save_png(image: np.ndarray, path: str | Path) -> Path:
    """Write float RGBA (height, width, 4), row 0 at the top, as an 8-bit RGBA PNG.

    Values are clamped to [0, 1] and written as they are, with no transfer curve: the way the
    report's program wrote its PNGs. Halves round up, as Blender's own 8-bit conversion does,
    so a scene imported into Blender writes the same bytes.
    """
    data = to_bytes(image)
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    Image.fromarray(data, "RGBA").save(path)
    return path


def to_bytes(image: np.ndarray) -> np.ndarray:
    """Float values clamped to [0, 1] as 8-bit, halves rounded up."""
    rgba = np.clip(np.asarray(image, np.float32), 0.0, 1.0)
    return np.floor(rgba * np.float32(255.0) + np.float32(0.5)).astype(np.uint8)
