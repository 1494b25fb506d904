"""The per-tile megakernel: camera rays for a rectangle of pixels, traced and averaged.

Each pixel averages its n x n camera rays (core.kernels.camera says where they go), or with
adaptive anti-aliasing first traces the pixel corners no neighbour has traced and the
pixel's centre, and weighs them where they agree (core.kernels.adaptive_tile).

A pixel's rays, corners and samples alike, go through one loop with one call of
`trace_ray`: the ray tracer is inlined where it is called, and each more call site would
be optimised again by LLVM (two more made the cold compile 3x as long).
"""

from ..jit.decorators import kernel
from .adaptive_tile import (
    CENTRE_SAMPLE,
    CORNER_SAMPLE,
    corner_mean,
    corner_of,
    corners_to_trace,
    keep_corner,
    next_corner_row,
    samples_differ,
)
from .camera import camera_ray, ray_through
from .features import WITH_ADAPTIVE, WITH_PASSES
from .integrator import trace_ray
from .light_samples import STRATA_KEY, STRATA_PLACE, STRATA_SIDE
from .options import OPTION_PASSES, OPTION_PIXEL_SAMPLES, OPTION_SEED
from .pass_record import accumulate, start_pixel, view_axis, write_passes
from .rng import PURPOSE_LENS, PURPOSE_LIGHT, chain, permuted, sample_key, uniform2

FLOAT32_MAX = 3.4028234663852886e38


@kernel
def render_tile(ps, image_width, image_height, x0, y0, width, height, out, ws):
    """Fill out[:height, :width] (float32: RGBA, then the passes asked for, as
    Frame.pass_offset lays them out) with pixels x0.. and y0.. of the image.

    Pixels depend only on their image coordinates, never on the tile, so any tiling of the
    image gives the same picture. The entry point the driver calls.
    Once ws.cancel[0] is set (by the driver, from another thread) it returns at the next
    pixel, leaving the rest of `out` as it was: a cancel is obeyed within one pixel's rays.
    """
    cancel = ws.cancel
    frame = ps.frame
    n = frame.options[OPTION_PIXEL_SAMPLES]
    samples = n * n
    seed = frame.options[OPTION_SEED]
    # passes and adaptive anti-aliasing are features a variant may leave out
    # (core.kernels.features): tested where their code is called
    passes = WITH_PASSES and frame.options[OPTION_PASSES] != 0
    axis = view_axis(frame)
    threshold = frame.sampling[0]
    adaptive = WITH_ADAPTIVE and threshold > 0.0 and n > 1
    corners = ws.corners
    strata = ws.stacks.light_strata
    for j in range(height):
        if WITH_ADAPTIVE and adaptive and j > 0:
            next_corner_row(corners)
        for i in range(width):
            if cancel[0] != 0:
                return
            px, py = x0 + i, y0 + j
            r = g = b = a = 0.0
            if WITH_PASSES and passes:
                start_pixel(ws.accum)
            # The pixel's key for sharing out the stratified lights' cells among its samples
            strata[STRATA_KEY] = chain(sample_key(seed, px, py, samples), PURPOSE_LIGHT)
            # Rays 0..first-1 (adaptive): the corners this pixel traces, then its centre;
            # then its samples, unless the corners and the centre agree
            first = 0
            if WITH_ADAPTIVE and adaptive:
                first = corners_to_trace(i, j) + 1
            end = first if adaptive else samples
            s = 0
            cr = cg = cb = ca = 0.0  # the centre's colour and alpha
            while s < end:
                # Corners and centres are no pixel's grid: their lights are sampled alone
                strata[STRATA_SIDE] = 0
                if s >= first and n > 1:
                    strata[STRATA_SIDE] = n
                    strata[STRATA_PLACE] = permuted(s - first, samples, strata[STRATA_KEY])
                if WITH_ADAPTIVE and s < first - 1:
                    cx, cy, column, row = corner_of(s, i, j)
                    key = sample_key(seed, x0 + cx, y0 + cy, CORNER_SAMPLE)
                    u, v = uniform2(key, PURPOSE_LENS, 0, 0)
                    o, d = ray_through(frame, image_width, image_height, float(x0 + cx),
                                       float(y0 + cy), u, v)  # fmt: skip
                elif WITH_ADAPTIVE and s < first:
                    key = sample_key(seed, px, py, CENTRE_SAMPLE)
                    u, v = uniform2(key, PURPOSE_LENS, 0, 0)
                    o, d = ray_through(frame, image_width, image_height, px + 0.5, py + 0.5,
                                       u, v)  # fmt: skip
                else:
                    key = sample_key(seed, px, py, s - first)
                    o, d = camera_ray(frame, image_width, image_height, px, py, s - first, key)
                colour, alpha = trace_ray(ps, o, d, key, ws)
                if WITH_ADAPTIVE and s < first - 1:
                    keep_corner(corners, row, column, colour, alpha, ws.record, passes)
                elif WITH_ADAPTIVE and s < first:
                    cr, cg, cb, ca = colour[0], colour[1], colour[2], alpha
                else:
                    r += colour[0]
                    g += colour[1]
                    b += colour[2]
                    a += alpha
                    if WITH_PASSES and passes:
                        accumulate(ws.accum, ws.crypto_ids, ws.record, s - first, frame, axis)
                s += 1
                if WITH_ADAPTIVE and adaptive and s == first:
                    if samples_differ(corners, i, (cr, cg, cb, ca), threshold):
                        end = first + samples  # they disagree: the pixel's own rays
                    elif WITH_PASSES and passes:
                        # they agree: the centre's record counts four times
                        for k in range(4):
                            accumulate(ws.accum, ws.crypto_ids, ws.record, 4 + k, frame, axis)
            count = end - first
            if WITH_ADAPTIVE and count == 0:  # they agreed: half the centre, an eighth each corner
                r, g, b, a = corner_mean(corners, i, ws, passes, frame, axis)
                r, g, b, a = r + 4.0 * cr, g + 4.0 * cg, b + 4.0 * cb, a + 4.0 * ca
                count = 8
            # Linear light has no upper bound, the float32 image has: saturate, never inf
            out[j, i, 0] = min(r / count, FLOAT32_MAX)
            out[j, i, 1] = min(g / count, FLOAT32_MAX)
            out[j, i, 2] = min(b / count, FLOAT32_MAX)
            out[j, i, 3] = a / count  # the share of camera rays that met something
            if WITH_PASSES and passes:
                write_passes(out, j, i, frame, ws.accum, ws.crypto_ids, ws.crypto_distinct, count)
