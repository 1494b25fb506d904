"""Loading texture images with Pillow into linear float RGB."""

from __future__ import annotations

import numpy as np
from PIL import Image, UnidentifiedImageError

from .errors import SceneError
from .scene_parts import Texture


def srgb_to_linear(c: np.ndarray) -> np.ndarray:
    """The sRGB transfer curve, inverted (IEC 61966-2-1)."""
    return np.where(c <= 0.04045, c / 12.92, ((c + 0.055) / 1.055) ** 2.4)


def load_texture(texture: Texture, owner: str) -> np.ndarray:
    """(h, w, 3) float32 linear RGB, row 0 at the top. Raises SceneError naming `owner`."""
    if texture.pixels is not None:
        rgb = np.asarray(texture.pixels, np.float64)[:, :, :3]
        if not np.all(np.isfinite(rgb)):
            raise SceneError(owner, "texture", "pixels contain NaN or infinity")
    else:
        try:
            with Image.open(texture.path) as image:
                rgb = np.asarray(image.convert("RGB"), np.float64) / 255.0
        except (UnidentifiedImageError, OSError, ValueError) as error:
            raise SceneError(
                owner,
                "texture",
                f"Pillow cannot read '{texture.path}' ({error}); use a PNG, JPEG or other "
                "image Pillow reads",
            ) from None
    if texture.srgb:
        rgb = srgb_to_linear(np.clip(rgb, 0.0, 1.0))
    return np.ascontiguousarray(rgb, np.float32)
