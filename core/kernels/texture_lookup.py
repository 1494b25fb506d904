"""Image Texture lookups as Blender makes them: Linear (bilinear) or Closest, and the four
extensions: Repeat, Extend (the edge texels go on), Clip (transparent black outside the
image) and Mirror. The vector's x and y are the image's u and v, v = 0 its bottom row."""

import math

from ..jit.decorators import kernel

# Image Texture interpolations and extensions (core.model.shader's, in that order)
INTERPOLATION_LINEAR, INTERPOLATION_CLOSEST = 0, 1
EXTENSION_REPEAT, EXTENSION_EXTEND, EXTENSION_CLIP, EXTENSION_MIRROR = 0, 1, 2, 3


@kernel
def _wrap(i, n, extension):
    """Texel index i of n along one axis, or -1 outside a clipped image."""
    if extension == EXTENSION_REPEAT:
        return i % n
    if extension == EXTENSION_EXTEND:
        return min(max(i, 0), n - 1)
    if extension == EXTENSION_CLIP:
        return i if 0 <= i < n else -1
    period = 2 * n
    j = i % period
    return j if j < n else period - 1 - j


@kernel
def _texel(mats, first, width, height, x, y, extension):
    """(RGB, alpha) of texel (x, y), y counted from the top row."""
    i, j = _wrap(x, width, extension), _wrap(y, height, extension)
    if i < 0 or j < 0:
        return (0.0, 0.0, 0.0), 0.0
    k = first + j * width + i
    pixels = mats.texture_pixels
    rgb = (float(pixels[k, 0]), float(pixels[k, 1]), float(pixels[k, 2]))
    return rgb, float(mats.texture_alpha[k])


@kernel
def image_lookup(mats, texture, vector, interpolation, extension):
    """(RGB, alpha) of texture row `texture` at the vector's (u, v)."""
    first = mats.texture_offset[texture]
    width, height = mats.texture_size[texture, 0], mats.texture_size[texture, 1]
    u, v = vector[0], vector[1]
    if not (math.isfinite(u) and math.isfinite(v)):
        return (0.0, 0.0, 0.0), 0.0
    if interpolation == INTERPOLATION_CLOSEST:
        x = int(math.floor(u * width))
        y = int(math.floor((1.0 - v) * height))
        return _texel(mats, first, width, height, x, y, extension)
    fx, fy = u * width - 0.5, (1.0 - v) * height - 0.5
    x0, y0 = math.floor(fx), math.floor(fy)
    tx, ty = fx - x0, fy - y0
    i, j = int(x0), int(y0)
    c00, a00 = _texel(mats, first, width, height, i, j, extension)
    c10, a10 = _texel(mats, first, width, height, i + 1, j, extension)
    c01, a01 = _texel(mats, first, width, height, i, j + 1, extension)
    c11, a11 = _texel(mats, first, width, height, i + 1, j + 1, extension)
    w00, w10 = (1.0 - tx) * (1.0 - ty), tx * (1.0 - ty)
    w01, w11 = (1.0 - tx) * ty, tx * ty
    rgb = (
        w00 * c00[0] + w10 * c10[0] + w01 * c01[0] + w11 * c11[0],
        w00 * c00[1] + w10 * c10[1] + w01 * c01[1] + w11 * c11[1],
        w00 * c00[2] + w10 * c10[2] + w01 * c01[2] + w11 * c11[2],
    )
    return rgb, w00 * a00 + w10 * a10 + w01 * a01 + w11 * a11
