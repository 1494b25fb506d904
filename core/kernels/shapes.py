"""The analytic shapes in object space: where a ray enters and leaves them, normals, UVs.

Every shape is intersected in its own object space, where it has its canonical size (see the
design: they match Blender's primitives). The ray is carried there by the inverse transform
without normalising its direction, so the hit parameter t is the same in both spaces.

The convex shapes (sphere, box, capped cylinder, capped cone) are solved as intervals: the
ray's parameter range inside the solid, each end labelled with the surface part it crosses
(a box face, the side or a cap). A capped cylinder is the infinite cylinder's interval
intersected with the slab -1 <= z <= 1, so there is no seam at a rim through which a ray
could slip between "side missed" and "cap missed": the two tests cannot disagree. The same
intervals serve CSG. The torus, which is not convex, lives in `core.kernels.torus`.

Shape kinds are integer constants switched on inside njit code, because a jitted function
passed around as a value would miss numba's cache in every new process.
"""

import math

from ..jit.decorators import kernel
from ..vocabulary import (  # noqa: F401  (the kinds, listed in core.vocabulary)
    SHAPE_BOX,
    SHAPE_CONE,
    SHAPE_CSG,
    SHAPE_CYLINDER,
    SHAPE_MESH,
    SHAPE_SPHERE,
    SHAPE_TORUS,
)
from .torus import torus_roots
from .vec import dot

# Surface parts: which piece of a shape a hit lies on
PART_SIDE = 0
PART_BOTTOM_CAP = 1  # z = -1
PART_TOP_CAP = 2  # z = +1
# Box faces are 2 * axis + (1 on the + side, 0 on the - side)

NO_HIT = math.inf
EMPTY = (math.inf, -1, -math.inf, -1)
EVERYWHERE = (-math.inf, -1, math.inf, -1)


@kernel
def stable_quadratic(a, b, c, discriminant):
    """Sorted roots of a t^2 + 2 b t + c = 0 given discriminant = b^2 - a c >= 0, a != 0,
    computed so that no root subtracts nearly equal numbers."""
    q = -(b + math.copysign(math.sqrt(discriminant), b))
    if q == 0.0:
        return 0.0, 0.0
    t0, t1 = q / a, c / q
    if t0 > t1:
        return t1, t0
    return t0, t1


@kernel
def slab(o, d, low_part, high_part):
    """Interval where -1 <= o + t d <= 1 along one axis, each end labelled with its part."""
    if d == 0.0:
        return EVERYWHERE if -1.0 <= o <= 1.0 else EMPTY
    t_low = (-1.0 - o) / d
    t_high = (1.0 - o) / d
    if t_low < t_high:
        return t_low, low_part, t_high, high_part
    return t_high, high_part, t_low, low_part


@kernel
def clip(a, b):
    """The intersection of two labelled intervals."""
    t0, p0 = (a[0], a[1]) if a[0] >= b[0] else (b[0], b[1])
    t1, p1 = (a[2], a[3]) if a[2] <= b[2] else (b[2], b[3])
    return t0, p0, t1, p1


@kernel
def sphere_interval(o, d):
    a = dot(d, d)
    b = dot(o, d)
    c = dot(o, o) - 1.0
    # b^2 - a c computed as a (1 - |o - (b/a) d|^2): no catastrophic cancellation for
    # distant or grazing rays (Ray Tracing Gems, chapter 7)
    s = b / a
    f0, f1, f2 = o[0] - s * d[0], o[1] - s * d[1], o[2] - s * d[2]
    discriminant = a * (1.0 - (f0 * f0 + f1 * f1 + f2 * f2))
    if discriminant < 0.0:
        return EMPTY
    t0, t1 = stable_quadratic(a, b, c, discriminant)
    return t0, PART_SIDE, t1, PART_SIDE


@kernel
def box_interval(o, d):
    result = slab(o[0], d[0], 0, 1)
    result = clip(result, slab(o[1], d[1], 2, 3))
    return clip(result, slab(o[2], d[2], 4, 5))


@kernel
def cylinder_interval(o, d):
    z_range = slab(o[2], d[2], PART_BOTTOM_CAP, PART_TOP_CAP)
    a = d[0] * d[0] + d[1] * d[1]
    if a == 0.0:
        inside = o[0] * o[0] + o[1] * o[1] <= 1.0
        return clip(z_range, EVERYWHERE) if inside else EMPTY
    b = o[0] * d[0] + o[1] * d[1]
    c = o[0] * o[0] + o[1] * o[1] - 1.0
    s = b / a
    f0, f1 = o[0] - s * d[0], o[1] - s * d[1]
    discriminant = a * (1.0 - (f0 * f0 + f1 * f1))
    if discriminant < 0.0:
        return EMPTY
    t0, t1 = stable_quadratic(a, b, c, discriminant)
    return clip(z_range, (t0, PART_SIDE, t1, PART_SIDE))


@kernel
def cone_interval(o, d):
    """The capped cone x^2 + y^2 <= ((1 - z) / 2)^2, -1 <= z <= 1.

    Along the ray, q(t) = x^2 + y^2 - w^2 with w = (1 - z) / 2 is a quadratic; where q <= 0
    the ray is inside the double cone. The lower nappe's part, clipped to the slab, is the
    solid: a convex one, so a single interval.
    """
    z_range = slab(o[2], d[2], PART_BOTTOM_CAP, PART_TOP_CAP)
    if z_range[0] > z_range[2]:
        return EMPTY
    # Solve from the ray's point nearest the centre, so the quadratic's coefficients are of
    # order one and b^2 - a c does not cancel catastrophically for distant rays (the same
    # idea as the sphere's discriminant); shift back at the end
    shift = -dot(o, d) / dot(d, d)
    q_t0, q_p0, q_t1, q_p1 = _cone_quadric_interval(
        (o[0] + shift * d[0], o[1] + shift * d[1], o[2] + shift * d[2]), d
    )
    return clip(z_range, (q_t0 + shift, q_p0, q_t1 + shift, q_p1))


@kernel
def _cone_quadric_interval(o, d):
    """Where x^2 + y^2 <= w^2 along the ray, lower nappe only (w = (1 - z) / 2 >= 0)."""
    w0 = 0.5 * (1.0 - o[2])
    wd = -0.5 * d[2]
    a = d[0] * d[0] + d[1] * d[1] - wd * wd
    b = o[0] * d[0] + o[1] * d[1] - w0 * wd
    c = o[0] * o[0] + o[1] * o[1] - w0 * w0
    if a == 0.0:
        # q is linear: 2 b t + c <= 0
        if b == 0.0:
            return EVERYWHERE if c <= 0.0 else EMPTY
        t = -c / (2.0 * b)
        if b > 0.0:
            return -math.inf, -1, t, PART_SIDE
        return t, PART_SIDE, math.inf, -1
    discriminant = b * b - a * c
    if discriminant < 0.0:
        # a > 0: q > 0 everywhere; a < 0: q < 0 everywhere
        return EMPTY if a > 0.0 else EVERYWHERE
    t0, t1 = stable_quadratic(a, b, c, discriminant)
    if a > 0.0:
        return t0, PART_SIDE, t1, PART_SIDE
    # a < 0: steeper than the cone, the line runs through both nappes and is inside on both
    # outer half-lines; keep the lower nappe's: the first going up, the second going down.
    # (An interval with a > 0 in the upper nappe is removed by the slab, z <= 1.)
    if d[2] > 0.0:
        return -math.inf, -1, t0, PART_SIDE
    return t1, PART_SIDE, math.inf, -1


@kernel
def convex_interval(kind, o, d):
    if kind == SHAPE_SPHERE:
        return sphere_interval(o, d)
    if kind == SHAPE_BOX:
        return box_interval(o, d)
    if kind == SHAPE_CYLINDER:
        return cylinder_interval(o, d)
    if kind == SHAPE_CONE:
        return cone_interval(o, d)
    return EMPTY


@kernel
def intersect_analytic(kind, major, minor, o, d, t_min, t_max):
    """(t, part) of the nearest crossing with t_min < t < t_max; (NO_HIT, -1) if none."""
    if kind == SHAPE_TORUS:
        n, r0, r1, r2, r3 = torus_roots(o, d, major, minor)
        if n > 0 and t_min < r0 < t_max:
            return r0, PART_SIDE
        if n > 1 and t_min < r1 < t_max:
            return r1, PART_SIDE
        if n > 2 and t_min < r2 < t_max:
            return r2, PART_SIDE
        if n > 3 and t_min < r3 < t_max:
            return r3, PART_SIDE
        return NO_HIT, -1
    t0, p0, t1, p1 = convex_interval(kind, o, d)
    if t0 > t1:
        return NO_HIT, -1
    if t_min < t0 < t_max:
        return t0, p0
    if t_min < t1 < t_max:
        return t1, p1
    return NO_HIT, -1


@kernel
def count_crossings(kind, major, minor, o, d, t_min, t_max):
    """How many times the ray crosses the shape's surface with t_min < t < t_max."""
    if kind == SHAPE_TORUS:
        n, r0, r1, r2, r3 = torus_roots(o, d, major, minor)
        count = 0
        for k, r in enumerate((r0, r1, r2, r3)):
            if k < n and t_min < r < t_max:
                count += 1
        return count
    t0, _, t1, _ = convex_interval(kind, o, d)
    if t0 > t1:
        return 0
    return int(t_min < t0 < t_max) + int(t_min < t1 < t_max)


@kernel
def analytic_normal(kind, major, p, part):
    """Outward normal (not normalised) at object-space point p on `part` of the shape."""
    if kind == SHAPE_SPHERE:
        return p
    if kind == SHAPE_BOX:
        axis = part // 2
        sign = 1.0 if part % 2 == 1 else -1.0
        return (sign if axis == 0 else 0.0, sign if axis == 1 else 0.0, sign if axis == 2 else 0.0)
    if part == PART_BOTTOM_CAP:
        return (0.0, 0.0, -1.0)
    if part == PART_TOP_CAP:
        return (0.0, 0.0, 1.0)
    if kind == SHAPE_CYLINDER:
        return (p[0], p[1], 0.0)
    if kind == SHAPE_CONE:
        # Gradient of x^2 + y^2 - ((1 - z) / 2)^2, halved; zero at the apex, where any
        # normal of the cone's tangent cone is as good: take the axis
        w = 0.5 * (1.0 - p[2])
        if p[0] == 0.0 and p[1] == 0.0 and w <= 0.0:
            return (0.0, 0.0, 1.0)
        return (p[0], p[1], 0.5 * w)
    if kind == SHAPE_TORUS:
        # From the nearest point of the tube's core circle: exact and stable
        rho = math.sqrt(p[0] * p[0] + p[1] * p[1])
        if rho == 0.0:
            return (0.0, 0.0, 1.0 if p[2] >= 0.0 else -1.0)
        k = major / rho
        return (p[0] - k * p[0], p[1] - k * p[1], p[2])
    return (0.0, 0.0, 1.0)


@kernel
def _around_z(p):
    """0..1 going once around the z axis, starting at -x (so u = 0.5 faces +x)."""
    return math.atan2(p[1], p[0]) / (2.0 * math.pi) + 0.5


@kernel
def analytic_uv(kind, major, p, part):
    """Texture coordinates (u, v) in [0, 1] of object-space point p, without the stretching
    of one planar projection: each part of a shape gets a mapping of its own.

    sphere    u around the z axis, v from the south pole (0) to the north pole (1)
    box       each face the whole image, upright on the sides, seen from outside
    cylinder  side: u around, v up the height; caps: the disk in the image's inscribed circle
    cone      side as the cylinder's; base as a cap
    torus     u around the ring, v around the tube
    """
    if kind == SHAPE_SPHERE:
        z = max(-1.0, min(1.0, p[2] / math.sqrt(dot(p, p))))
        return _around_z(p), 0.5 + math.asin(z) / math.pi
    if kind == SHAPE_BOX:
        x, y, z = 0.5 * (p[0] + 1.0), 0.5 * (p[1] + 1.0), 0.5 * (p[2] + 1.0)
        if part == 0:
            return 1.0 - y, z
        if part == 1:
            return y, z
        if part == 2:
            return x, z
        if part == 3:
            return 1.0 - x, z
        if part == 4:
            return x, 1.0 - y
        return x, y
    if part == PART_TOP_CAP:
        return 0.5 * (p[0] + 1.0), 0.5 * (p[1] + 1.0)
    if part == PART_BOTTOM_CAP:
        return 0.5 * (p[0] + 1.0), 0.5 * (1.0 - p[1])
    if kind == SHAPE_TORUS:
        rho = math.sqrt(p[0] * p[0] + p[1] * p[1])
        return _around_z(p), math.atan2(p[2], rho - major) / (2.0 * math.pi) + 0.5
    # The sides of the cylinder and the cone
    return _around_z(p), 0.5 * (p[2] + 1.0)
