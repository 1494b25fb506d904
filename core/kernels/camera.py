"""Camera rays: where a camera sample lies in its pixel and on the lens.

A pixel averages n x n camera rays, one per cell of an n x n grid over the pixel: at the
cell centres ("grid", the report's 3 x 3 supersampling when n = 3) or at a random point in
each cell ("jittered"). With a lens (aperture > 0) each ray starts at a point on the lens,
also stratified over n x n cells of the lens (in a random order per pixel, so that the pixel and
lens positions are not correlated), and aims at where the pinhole ray meets the plane in
focus. With aperture 0 the lens code does not run: the pinhole picture, exactly. The lens is
a disk, or a regular polygon with the camera's blades (polygonal bokeh), and its width may be
divided by an aspect ratio (anamorphic bokeh), as Blender's Aperture panel sets it.

Adaptive anti-aliasing's corner rays (core.kernels.adaptive_tile) go through the same code
at a pixel corner, their lens point at random over the whole lens.
"""

from ..jit.decorators import inlined_kernel, kernel
from .light_samples import concentric_disk, regular_polygon
from .options import (
    OPTION_PIXEL_PATTERN,
    OPTION_PIXEL_SAMPLES,
    OPTION_PROJECTION,
    OPTION_SEED,
    PIXEL_GRID,
    PIXEL_RANDOM,
    PROJECTION_ORTHOGRAPHIC,
)
from .rng import PURPOSE_LENS, PURPOSE_PIXEL, permuted, sample_key, uniform2
from .vec import add, normalize, row, scale, sub


@kernel
def camera_ray(frame, image_width, image_height, px, py, sample, key):
    """(origin, unit direction) of camera sample `sample` of pixel (px, py), py from the top."""
    n = frame.options[OPTION_PIXEL_SAMPLES]
    pattern = frame.options[OPTION_PIXEL_PATTERN]
    cx, cy = sample % n, sample // n
    jx, jy = 0.5, 0.5
    if pattern != PIXEL_GRID:
        jx, jy = uniform2(key, PURPOSE_PIXEL, 0, 0)
    fx, fy = (cx + jx) / n, (cy + jy) / n
    if pattern == PIXEL_RANDOM:
        fx, fy = jx, jy
    if frame.lens[0] == 0.0:
        return ray_through(frame, image_width, image_height, px + fx, py + fy, 0.0, 0.0)
    # Lens cells in a random order of the pixel's own, so that a pixel's sub-position and
    # its lens position are not correlated (a fixed stride made a lattice that biased some
    # n: the depth-of-field chart's error rose from 144 to 256 rays)
    pixel_key = sample_key(frame.options[OPTION_SEED], px, py, n * n)
    cell = permuted(sample, n * n, pixel_key)
    a, b = uniform2(key, PURPOSE_LENS, 0, 0)
    u, v = ((cell % n) + a) / n, ((cell // n) + b) / n
    return ray_through(frame, image_width, image_height, px + fx, py + fy, u, v)


@inlined_kernel
def ray_through(frame, image_width, image_height, x, y, u, v):
    """(origin, unit direction) of the ray through image point (x, y) (in pixels from the
    top left corner) from lens point (u, v) of the unit square (unused without a lens).
    Inlined: a call passes the frame's arrays field by field, per camera ray."""
    sx = 2.0 * x / image_width - 1.0
    sy = 1.0 - 2.0 * y / image_height
    eye = row(frame.camera, 0)
    right, up = row(frame.camera, 2), row(frame.camera, 3)
    offset = add(scale(right, sx), scale(up, sy))
    if frame.options[OPTION_PROJECTION] == PROJECTION_ORTHOGRAPHIC:
        # Parallel rays, each from its own point of the image plane through the eye; the
        # lens below then works about that point as it does about the eye
        eye, d = add(eye, offset), row(frame.camera, 1)
    else:
        d = add(row(frame.camera, 1), offset)
    aperture = frame.lens[0]
    if aperture == 0.0:
        return eye, normalize(d)
    # d has unit length along the view direction, so eye + f d lies on the focal plane
    focus = add(eye, scale(d, frame.lens[1]))
    blades = int(frame.lens[2])
    if blades == 0:
        lx, ly = concentric_disk(u, v)
    else:
        lx, ly = regular_polygon(blades, frame.lens[3], u, v)
    lx *= frame.lens[4]  # 1 / the aperture ratio
    origin = add(
        eye, add(scale(normalize(right), aperture * lx), scale(normalize(up), aperture * ly))
    )
    return origin, normalize(sub(focus, origin))
