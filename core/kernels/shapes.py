"""Intersection of rays with the canonical shapes, in object space.

Every shape is intersected in its own object space, where it has its canonical size (see the
design: they match Blender's primitives). The ray is carried there by the inverse transform
without normalising its direction, so the hit parameter t is the same in both spaces.

Intersection runs in two stages: `intersect_shape` returns only the distance t, for every
candidate; `object_normal` builds the surface normal once, for the closest hit.
Shape kinds are integer constants switched on inside njit code, because a jitted function
passed around as a value would miss numba's cache in every new process.
"""

import math

from core.jit import kernel
from core.kernels.vec import dot, scale, sub

SHAPE_SPHERE = 0

NO_HIT = math.inf


@kernel
def intersect_unit_sphere(o, d, t_min, t_max):
    """Nearest t in (t_min, t_max) where o + t d meets the unit sphere, else NO_HIT."""
    # Quadratic a t^2 + 2 b t + c = 0
    a = dot(d, d)
    b = dot(o, d)
    c = dot(o, o) - 1.0
    # Discriminant b^2 - a c computed as a (1 - |o - (b/a) d|^2): no catastrophic
    # cancellation for distant or grazing rays (Ray Tracing Gems, chapter 7)
    f = sub(o, scale(d, b / a))
    discriminant = a * (1.0 - dot(f, f))
    if discriminant < 0.0:
        return NO_HIT
    # Stable roots: q never subtracts nearly equal numbers
    q = -(b + math.copysign(math.sqrt(discriminant), b))
    if q == 0.0:
        t_near = t_far = 0.0
    else:
        t_near = q / a
        t_far = c / q
        if t_near > t_far:
            t_near, t_far = t_far, t_near
    if t_min < t_near < t_max:
        return t_near
    if t_min < t_far < t_max:
        return t_far
    return NO_HIT


@kernel
def intersect_shape(kind, o, d, t_min, t_max):
    """Nearest t in (t_min, t_max) on the canonical shape of `kind`, in object space."""
    if kind == SHAPE_SPHERE:
        return intersect_unit_sphere(o, d, t_min, t_max)
    return NO_HIT


@kernel
def object_normal(kind, p):
    """Outward normal (not normalised) of the canonical shape at object-space point p."""
    if kind == SHAPE_SPHERE:
        return p
    return (0.0, 0.0, 1.0)
