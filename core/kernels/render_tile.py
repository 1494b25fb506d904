"""The per-tile megakernel: camera rays for a rectangle of pixels, traced and shaded."""

import numpy as np

from core.jit import kernel
from core.kernels.shading import shade
from core.kernels.trace import closest_hit, world_normal
from core.kernels.vec import add, as_tuple, normalize, row, scale


@kernel
def camera_ray_direction(ps, image_width, image_height, px, py):
    """Unit direction through the centre of pixel (px, py), py counted from the top row."""
    sx = 2.0 * (px + 0.5) / image_width - 1.0
    sy = 1.0 - 2.0 * (py + 0.5) / image_height
    d = add(row(ps.camera, 1), add(scale(row(ps.camera, 2), sx), scale(row(ps.camera, 3), sy)))
    return normalize(d)


@kernel
def trace_camera_ray(ps, o, d):
    shape, t = closest_hit(ps, o, d, np.inf)
    if shape < 0:
        return as_tuple(ps.background)
    p = add(o, scale(d, t))
    return shade(ps, shape, p, world_normal(ps, shape, p), d, o)


@kernel
def render_tile(ps, image_width, image_height, x0, y0, width, height, out):
    """Fill out[:height, :width] (float32 RGBA) with pixels x0.. and y0.. of the image.

    Pixels depend only on their image coordinates, never on the tile, so any tiling of the
    image gives the same picture.
    """
    eye = row(ps.camera, 0)
    for j in range(height):
        for i in range(width):
            d = camera_ray_direction(ps, image_width, image_height, x0 + i, y0 + j)
            colour = trace_camera_ray(ps, eye, d)
            out[j, i, 0] = colour[0]
            out[j, i, 1] = colour[1]
            out[j, i, 2] = colour[2]
            out[j, i, 3] = 1.0
