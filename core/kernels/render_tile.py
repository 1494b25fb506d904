"""The per-tile megakernel: camera rays for a rectangle of pixels, traced and averaged.

A pixel averages n x n camera rays, one per cell of an n x n grid over the pixel: at the
cell centres ("grid", the report's 3 x 3 supersampling when n = 3) or at a random point in
each cell ("jittered"). With a lens (aperture > 0) each ray starts at a point on the lens,
also stratified over n x n cells of the lens (in a random order per pixel, so that the pixel and
lens positions are not correlated), and aims at where the pinhole ray meets the plane in
focus. With aperture 0 the lens code does not run: the pinhole picture, exactly. The lens is
a disk, or a regular polygon with the camera's blades (polygonal bokeh), and its width may be
divided by an aspect ratio (anamorphic bokeh), as Blender's Aperture panel sets it.
"""

from ..jit import kernel
from .borrow import borrowed
from .integrator import trace_ray
from .light_samples import concentric_disk, regular_polygon
from .options import (
    OPTION_PASSES,
    OPTION_PIXEL_PATTERN,
    OPTION_PIXEL_SAMPLES,
    OPTION_PROJECTION,
    OPTION_SEED,
    PIXEL_GRID,
    PIXEL_RANDOM,
    PROJECTION_ORTHOGRAPHIC,
)
from .pass_record import accumulate, start_pixel, view_axis, write_passes
from .rng import PURPOSE_LENS, PURPOSE_PIXEL, permuted, sample_key, uniform2
from .vec import add, normalize, row, scale, sub

FLOAT32_MAX = 3.4028234663852886e38


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
    sx = 2.0 * (px + fx) / image_width - 1.0
    sy = 1.0 - 2.0 * (py + fy) / image_height
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
    # Lens cells in a random order of the pixel's own, so that a pixel's sub-position and
    # its lens position are not correlated (a fixed stride made a lattice that biased some
    # n: the depth-of-field chart's error rose from 144 to 256 rays)
    pixel_key = sample_key(frame.options[OPTION_SEED], px, py, n * n)
    cell = permuted(sample, n * n, pixel_key)
    a, b = uniform2(key, PURPOSE_LENS, 0, 0)
    u, v = ((cell % n) + a) / n, ((cell // n) + b) / n
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


@kernel
def render_tile(ps, image_width, image_height, x0, y0, width, height, out, ws):
    """Fill out[:height, :width] (float32: RGBA, then the passes asked for, as
    Frame.pass_offset lays them out) with pixels x0.. and y0.. of the image.

    Pixels depend only on their image coordinates, never on the tile, so any tiling of the
    image gives the same picture. The entry point the driver calls: it borrows its arrays
    for the tile's duration (see core.kernels.borrow), so no reference counting runs below.
    Once ws.cancel[0] is set (by the driver, from another thread) it returns at the next
    pixel, leaving the rest of `out` as it was: a cancel is obeyed within one pixel's rays.
    """
    ps, ws, out = borrowed(ps), borrowed(ws), borrowed(out)
    cancel = ws.cancel
    frame = ps.frame
    n = frame.options[OPTION_PIXEL_SAMPLES]
    samples = n * n
    seed = frame.options[OPTION_SEED]
    passes = frame.options[OPTION_PASSES] != 0
    axis = view_axis(frame)
    for j in range(height):
        for i in range(width):
            if cancel[0] != 0:
                return
            px, py = x0 + i, y0 + j
            r = g = b = a = 0.0
            if passes:
                start_pixel(ws.accum)
            for s in range(samples):
                key = sample_key(seed, px, py, s)
                o, d = camera_ray(frame, image_width, image_height, px, py, s, key)
                colour, alpha = trace_ray(ps, o, d, key, ws)
                r += colour[0]
                g += colour[1]
                b += colour[2]
                a += alpha
                if passes:
                    accumulate(ws.accum, ws.crypto_ids, ws.record, s, frame, axis)
            # Linear light has no upper bound, the float32 image has: saturate, never inf
            out[j, i, 0] = min(r / samples, FLOAT32_MAX)
            out[j, i, 1] = min(g / samples, FLOAT32_MAX)
            out[j, i, 2] = min(b / samples, FLOAT32_MAX)
            out[j, i, 3] = a / samples  # the share of camera rays that met something
            if passes:
                write_passes(out, j, i, frame, ws.accum, ws.crypto_ids, ws.crypto_distinct, samples)
