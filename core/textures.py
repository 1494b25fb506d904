"""Loading texture images with Pillow into linear float RGB."""

from __future__ import annotations

import contextlib
import hashlib
import os
import threading
import warnings
from collections import OrderedDict

import numpy as np
from PIL import Image, UnidentifiedImageError

from .errors import SceneError
from .model import Texture

# 8192 x 8192: 0.8 GB as the kernels' float32 RGB. A small PNG can hold far more pixels (a
# 140 KB file of one colour unpacked to 5.2 GB), so the size is read before the pixels
MAX_TEXTURE_PIXELS = 2**26
# Decoded image files kept for the next compile of the process (the viewport compiles on every
# edit, an animation every frame): decoding and linearising the final scene's three textures
# was 27 of its 38 ms of compile. Keyed by file and modification time, so an edited file is
# read again; at most this many bytes of float32 pixels are kept, the least recently used
# dropped first
TEXTURE_CACHE_BYTES = 512 * 2**20
_decoded: OrderedDict = OrderedDict()
_decoded_lock = threading.Lock()


@contextlib.contextmanager
def open_image(path):
    """Pillow's Image.open, without its warning past 89 M pixels: our own, smaller limit
    (too_large) decides, with a message of its own."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", Image.DecompressionBombWarning)
        with Image.open(path) as image:
            yield image


def too_large(size: tuple[int, int]) -> str | None:
    """Why an image of (width, height) is refused as a texture, or None."""
    width, height = size
    if width * height <= MAX_TEXTURE_PIXELS:
        return None
    return (
        f"is {width} x {height} pixels; textures of up to {MAX_TEXTURE_PIXELS:,} pixels "
        "(8192 x 8192) are read: scale it down"
    )


def srgb_to_linear(c: np.ndarray) -> np.ndarray:
    """The sRGB transfer curve, inverted (IEC 61966-2-1)."""
    return np.where(c <= 0.04045, c / 12.92, ((c + 0.055) / 1.055) ** 2.4)


def load_texture(texture: Texture, owner: str) -> np.ndarray:
    """(h, w, 3) float32 linear RGB, row 0 at the top. Raises SceneError naming `owner`."""
    if texture.pixels is not None:
        return _load_pixels(texture, owner)
    try:
        stat = os.stat(texture.path)
        key = (os.path.abspath(texture.path), stat.st_mtime_ns, stat.st_size, texture.srgb)
    except (OSError, TypeError, ValueError):
        key = None  # unreadable: decoding it below names the problem
    with _decoded_lock:
        if key in _decoded:
            _decoded.move_to_end(key)
            return _decoded[key]
    pixels = _linear(_decode(texture, owner), texture.srgb)
    pixels.flags.writeable = False  # shared by every compile that uses the file
    if key is not None:
        _remember(key, pixels)
    return pixels


def _load_pixels(texture: Texture, owner: str) -> np.ndarray:
    """A texture given as pixels (Blender's images): kept by their content, since Blender
    hands over a fresh copy of the same pixels for every render (linearising the final
    scene's images again was 40 of a farm border's 100 ms beyond its render)."""
    given = np.ascontiguousarray(texture.pixels)
    if given.dtype.kind not in "biuf":  # not numbers: converting says what is wrong
        given = np.ascontiguousarray(given, np.float64)
    digest = hashlib.blake2b(given.view(np.uint8), digest_size=16).digest()
    key = ("pixels", given.shape, given.dtype.str, texture.srgb, digest)
    with _decoded_lock:
        if key in _decoded:
            _decoded.move_to_end(key)
            return _decoded[key]
    rgb = np.asarray(given, np.float64)[:, :, :3]
    if not np.all(np.isfinite(rgb)):
        raise SceneError(owner, "texture", "pixels contain NaN or infinity")
    pixels = _linear(rgb, texture.srgb)
    pixels.flags.writeable = False
    _remember(key, pixels)
    return pixels


def _remember(key, pixels: np.ndarray) -> None:
    with _decoded_lock:
        _decoded[key] = pixels
        while sum(p.nbytes for p in _decoded.values()) > TEXTURE_CACHE_BYTES and _decoded:
            _decoded.popitem(last=False)


def _decode(texture: Texture, owner: str) -> np.ndarray:
    """The image file's RGB in 0..1, float64."""
    try:
        with open_image(texture.path) as image:
            if problem := too_large(image.size):
                raise SceneError(owner, "texture", f"'{texture.path}' {problem}")
            rgb = np.asarray(image.convert("RGB"), np.float64) / 255.0
    except Image.DecompressionBombError:  # past Pillow's own limit, which is larger
        raise SceneError(
            owner, "texture", f"'{texture.path}' has more pixels than any texture needs"
        ) from None
    except (UnidentifiedImageError, OSError, ValueError) as error:
        raise SceneError(
            owner,
            "texture",
            f"Pillow cannot read '{texture.path}' ({error}); use a PNG, JPEG or other "
            "image Pillow reads",
        ) from None
    return rgb


def _linear(rgb: np.ndarray, srgb: bool) -> np.ndarray:
    if srgb:
        rgb = srgb_to_linear(np.clip(rgb, 0.0, 1.0))
    return np.ascontiguousarray(rgb, np.float32)
