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
from .exr_read import MAGIC, ExrError, read_exr_rgb
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
EXR_MAGIC = MAGIC.to_bytes(4, "little")
_decoded: OrderedDict = OrderedDict()
_decoded_lock = threading.Lock()


@contextlib.contextmanager
def open_image(path):
    """Pillow's Image.open, without its warning past 89 M pixels: our own, smaller limit
    (too_large) decides, with a message of its own."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", Image.DecompressionBombWarning)
        # A damaged file's metadata (Pillow's "Corrupt EXIF data"): the pixels still count
        warnings.simplefilter("ignore", UserWarning)
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
    """The image file's RGB, float64, at its true values."""
    try:
        return read_rgb(texture.path)
    except ImageFileError as problem:
        raise SceneError(owner, "texture", f"'{texture.path}' {problem}") from None


class ImageFileError(Exception):
    """Why an image file cannot be a texture, as the end of a sentence naming the file."""


def read_rgb(path) -> np.ndarray:
    """(h, w, 3) float64 RGB of the image file at its true values: 0..1 for 8 and 16-bit
    integers, as stored for floating point (float TIFF, OpenEXR). Raises ImageFileError."""
    rgb = (_read_exr if _is_exr(path) else _read_with_pillow)(path)
    if not np.all(np.isfinite(rgb)):
        raise ImageFileError("holds NaN or infinite values; a texture's values are finite")
    return rgb


def _is_exr(path) -> bool:
    """Told by its first bytes, as Pillow tells its formats: not by the name's suffix."""
    try:
        with open(path, "rb") as file:
            return file.read(4) == EXR_MAGIC
    except OSError:
        return False  # Pillow's opening says why


def _read_exr(path) -> np.ndarray:
    try:
        with open(path, "rb") as file:
            return read_exr_rgb(file.read(), too_large)
    except ExrError as problem:
        raise ImageFileError(str(problem)) from None
    except OSError as error:
        raise ImageFileError(f"cannot be read: {error.strerror or error}") from None
    except MemoryError:
        raise ImageFileError("needs more memory to decode than is free") from None


def _read_with_pillow(path) -> np.ndarray:
    try:
        with open_image(path) as image:
            if problem := too_large(image.size):
                raise ImageFileError(problem)
            image.verify()  # checksums (a PNG's CRCs), which decoding alone does not read
        with open_image(path) as image:
            rgb = true_rgb(image)
    except Image.DecompressionBombError:  # past Pillow's own limit, which is larger
        raise ImageFileError("has more pixels than any texture needs") from None
    except ImageFileError:
        raise
    except MemoryError:
        raise ImageFileError("needs more memory to decode than is free") from None
    except Exception as error:  # noqa: BLE001 - a broken file can fail anywhere in a decoder
        raise ImageFileError(_decoder_problem(error)) from None
    return rgb


def true_rgb(image: Image.Image) -> np.ndarray:
    """An opened image's colour channels as float64 RGB at their true values. Pillow's own
    convert("RGB") clips 16-bit and float images to 8 bits (a 16-bit grey PNG came out all
    white, a float TIFF of 0.5 all black). Alpha is not colour, and is dropped."""
    mode = image.mode
    if mode in ("RGBa", "P", "PA"):  # premultiplied or indexed: as straight RGB(A)
        image, mode = image.convert("RGBA"), "RGBA"
    if mode in _GREY_SCALES:
        grey = np.asarray(image).astype(np.float64) / _GREY_SCALES[mode]
        if mode == "I" and grey.size and (grey.max() > 1.0 or grey.min() < 0.0):
            raise ImageFileError(
                "holds 32-bit integer samples beyond 16 bits; save it as 16-bit or float"
            )
        return np.repeat(grey[:, :, None], 3, axis=2)
    if mode in ("LA", "La"):
        grey_alpha = np.asarray(image).astype(np.float64)
        grey = grey_alpha[:, :, 0] / 255.0
        if mode == "La":  # premultiplied by alpha, which Pillow does not convert: undone here
            alpha = grey_alpha[:, :, 1] / 255.0
            grey = np.divide(grey, alpha, out=np.zeros_like(grey), where=alpha > 0)
        return np.repeat(grey[:, :, None], 3, axis=2)
    if mode not in ("RGB", "RGBA", "RGBX"):  # CMYK, YCbCr, LAB, HSV: Pillow's conversions
        image, mode = image.convert("RGB"), "RGB"
    return np.asarray(image)[:, :, :3].astype(np.float64) / 255.0


# Grey modes and the value that is white in each. Pillow reads 16-bit greys as I;16 (or as I,
# 32-bit, from some formats): both hold the file's 16-bit values
_GREY_SCALES = {
    "1": 1.0,
    "L": 255.0,
    "I;16": 65535.0,
    "I;16L": 65535.0,
    "I;16B": 65535.0,
    "I;16N": 65535.0,
    "I": 65535.0,
    "F": 1.0,
}


def _decoder_problem(error: Exception) -> str:
    """A decoder's exception as the rest of a sentence, with what to do where it is plain."""
    said = str(error) or type(error).__name__
    if "decompressed data too large" in said.lower() or "text chunks" in said:
        return (
            f"holds a text chunk (metadata) larger than Pillow decompresses ({said}); save "
            "the image again without its metadata"
        )
    if isinstance(error, UnidentifiedImageError):
        return "is not an image Pillow reads; use a PNG, JPEG, TIFF or other common image"
    return (
        f"cannot be decoded ({type(error).__name__}: {said[:200]}); the file is damaged or "
        "of a kind Pillow does not read: save it again as a PNG"
    )


def _linear(rgb: np.ndarray, srgb: bool) -> np.ndarray:
    if srgb:
        rgb = srgb_to_linear(np.clip(rgb, 0.0, 1.0))
    return np.ascontiguousarray(rgb, np.float32)
