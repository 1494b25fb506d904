"""Where a light's shadow rays go: points of the unit square in the render's shadow pattern,
carried onto disks and around directions.

The unit square's points are those the report's area lights use (stratified, uniform or
Halton, `core.kernels.shading`); every light in Blender's units maps them onto its own shape
with maps that keep areas in proportion, so a stratified pattern stays stratified on a disk, a
sphere's cone of directions or a sun's.
"""

import math

import numpy as np

from ..jit.decorators import inlined_kernel, kernel
from .options import SHADOW_HALTON, SHADOW_STRATIFIED
from .rng import PURPOSE_LIGHT, chain, mix, uniform2
from .vec import add, scale


@kernel
def radical_inverse(i, base):
    """The digits of i in `base` mirrored about the point: the Halton sequence's i-th
    coordinate in that base, in [0, 1)."""
    inverse, scale_ = 0.0, 1.0 / base
    while i > 0:
        inverse += (i % base) * scale_
        i //= base
        scale_ /= base
    return inverse


@kernel
def stratified_cell(j, count):
    """Cell j of `count` equal-area cells tiling the unit square: (x0, y0, width, height).

    Rows of ceil(sqrt(count)) cells; a short last row gets wider cells and a taller row, so
    every cell has area 1/count and the cells cover the square exactly once."""
    columns = int(math.ceil(math.sqrt(count)))
    rows = (count + columns - 1) // columns
    r = j // columns
    in_row = columns if r < rows - 1 else count - columns * (rows - 1)
    height = in_row / count
    y0 = columns * r / count
    return (j - r * columns) / in_row, y0, 1.0 / in_row, height


# Slots of Stacks.light_strata: where the camera sample being traced stands in its pixel's
# random order of its n x n samples, n (0: the sample is not one of a pixel's grid), and the
# pixel's key
STRATA_PLACE, STRATA_SIDE, STRATA_KEY = 0, 1, 2
STRATA_SLOTS = 3


@inlined_kernel
def light_spread(strata, pattern, samples, stream):
    """Where on a light this camera sample's one shadow ray goes, when each of its pixel's
    n x n camera samples casts one (see `square_point`): (column, row, n) of its cell of an
    n x n division of the light; n 0 when the pattern is not stratified, the camera sample
    is no pixel's grid or it casts more than one ray. The cell is the sample's place in its
    pixel's random order, turned by an offset of the light's and the bounce's own
    (`stream`), so that each light sees the pixel's samples in another order. Worked out
    once per light, the order once per camera ray: a random permutation per light point
    cost the final scene 15% of its render time."""
    side = int(strata[STRATA_SIDE])
    if pattern != SHADOW_STRATIFIED or side < 2 or samples != 1:
        return 0, 0, 0
    count = side * side
    # The hash's top 32 bits scaled to 0..count-1 (count is at most 1024^2): no division
    h = mix(chain(strata[STRATA_KEY], stream)) >> np.uint64(32)
    cell = int(strata[STRATA_PLACE]) + int((h * np.uint64(count)) >> np.uint64(32))
    if cell >= count:
        cell -= count
    return cell % side, cell // side, side


@inlined_kernel
def square_point(pattern, samples, j, key, stream, shift, spread):
    """Point j of `samples` in the unit square, in the shadow `pattern`; `shift` is the
    shading point's Halton offset, `key` and `stream` select the random numbers.

    Stratified, point j lies in cell j of `samples` equal cells; and where each of a pixel's
    n x n camera samples casts one ray, they share out n x n cells of the light (`spread`,
    from `light_spread`), each its own, in a random order of the pixel's, so that its place
    in the pixel and its place on the light are not correlated: the pixel's mean sees the
    light stratified n x n times as finely, at no more rays (Cook, Porter and Carpenter's
    distributed ray tracing gives each of a pixel's rays its own part of the light). On the
    final scene at one shadow ray a camera ray, RMSE against the converged picture 0.00477
    -> 0.00434 at 3 x 3 camera rays, 0.00182 -> 0.00148 at 6 x 6
    (tests/benchmarks/bench_equal_error). With more rays a camera ray, their cells stay
    each camera ray's own: dividing each cell among the pixel's samples made each camera
    ray's points a near-lattice, and sharing bands of cells out made them stripes; either
    raised the teapot's soft-shadow error (2 x 2 camera rays, 4 to 25 shadow rays) by
    1.2-1.9x (tests/blender/test_adaptive_samples)."""
    if pattern == SHADOW_HALTON:
        a = (radical_inverse(j + 1, 2) + shift[0]) % 1.0
        b = (radical_inverse(j + 1, 3) + shift[1]) % 1.0
    else:
        a, b = uniform2(key, PURPOSE_LIGHT, stream, j)
    if pattern == SHADOW_STRATIFIED:
        column, row, side = spread
        if side > 0:
            return (column + a) / side, (row + b) / side
        x0, y0, w, h = stratified_cell(j, samples)
        a, b = x0 + a * w, y0 + b * h
    return a, b


@kernel
def concentric_disk(a, b):
    """The unit square onto the unit disk, areas in proportion and neighbours kept together
    (Shirley and Chiu's concentric map): squares about the centre become rings. (A lens's
    points too, core.kernels.render_tile.)"""
    x, y = 2.0 * a - 1.0, 2.0 * b - 1.0
    if x == 0.0 and y == 0.0:
        return 0.0, 0.0
    if abs(x) > abs(y):
        r, phi = x, (math.pi / 4.0) * (y / x)
    else:
        r, phi = y, math.pi / 2.0 - (math.pi / 4.0) * (x / y)
    return r * math.cos(phi), r * math.sin(phi)


@kernel
def regular_polygon(corners, rotation, a, b):
    """The unit square onto the regular polygon with `corners` corners on the unit circle,
    turned by `rotation` radians (a camera's aperture blades): `a` picks one of the triangles
    fanned from the centre, corner k at angle rotation + (2k + 1) pi / corners, and with `b`
    places the point in it uniformly, so the polygon is covered with even density."""
    scaled = a * corners
    wedge = min(math.floor(scaled), corners - 1)
    a = scaled - wedge
    # Uniform in the triangle (centre, c0, c1): sqrt(a) reaches out from the centre, b slides
    # between the two corners
    reach = math.sqrt(a)
    first = rotation + (2.0 * wedge + 1.0) * math.pi / corners
    second = first + 2.0 * math.pi / corners
    x = reach * ((1.0 - b) * math.cos(first) + b * math.cos(second))
    y = reach * ((1.0 - b) * math.sin(first) + b * math.sin(second))
    return x, y


@kernel
def basis(w):
    """Two unit vectors that make a right-handed orthonormal frame with unit w, continuous in
    w except where w's z changes sign (Duff et al. 2017)."""
    sign = math.copysign(1.0, w[2])
    a = -1.0 / (sign + w[2])
    b = w[0] * w[1] * a
    e1 = (1.0 + sign * w[0] * w[0] * a, sign * b, -sign * w[0])
    e2 = (b, sign + w[1] * w[1] * a, -w[1])
    return e1, e2


@kernel
def in_frame(w, x, y, z):
    """x e1 + y e2 + z w in the frame `basis` makes around unit w."""
    e1, e2 = basis(w)
    return add(add(scale(e1, x), scale(e2, y)), scale(w, z))


@kernel
def cone_direction(w, one_minus_cos_max, a, b):
    """A direction within the cone about unit w whose half-angle has 1 - cos = the given
    (exact for tiny cones, where cos itself rounds to 1), uniform in solid angle."""
    one_minus = a * one_minus_cos_max
    cos_theta = 1.0 - one_minus
    sin_theta = math.sqrt(max(0.0, one_minus * (2.0 - one_minus)))
    phi = 2.0 * math.pi * b
    return in_frame(w, sin_theta * math.cos(phi), sin_theta * math.sin(phi), cos_theta)
