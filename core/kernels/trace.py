"""Rays against the whole scene: nearest hit, any hit, and where secondary rays start.

The shape loop is linear for now; the BVH replaces it behind these same two functions.
"""

from core.jit import kernel
from core.kernels.shapes import NO_HIT, intersect_shape, object_normal
from core.kernels.vec import (
    add,
    affine_point,
    affine_transpose_vector,
    affine_vector,
    max_abs,
    normalize,
    scale,
)

# Secondary rays start this far off the surface, relative to the magnitude of the
# coordinates involved: float64 hit points are accurate to a few ulps of that magnitude, so a
# relative offset stays clear of self-intersection at every scene scale where a fixed epsilon
# fails at one end or the other (Waechter and Binder, Ray Tracing Gems, chapter 6).
SPAWN_OFFSET_RELATIVE = 1e-9
SPAWN_OFFSET_ABSOLUTE = 1e-30


@kernel
def closest_hit(ps, o, d, t_max):
    """(shape index, t) of the nearest hit along o + t d with 0 < t < t_max; (-1, NO_HIT)."""
    best_shape = -1
    best_t = t_max
    for i in range(ps.shape_kind.shape[0]):
        m = ps.shape_object_from_world[i]
        t = intersect_shape(ps.shape_kind[i], affine_point(m, o), affine_vector(m, d), 0.0, best_t)
        if t < best_t:
            best_t = t
            best_shape = i
    if best_shape < 0:
        return -1, NO_HIT
    return best_shape, best_t


@kernel
def occluded(ps, o, d, t_max):
    """Whether anything lies along o + t d with 0 < t < t_max (shadow rays)."""
    for i in range(ps.shape_kind.shape[0]):
        m = ps.shape_object_from_world[i]
        t = intersect_shape(ps.shape_kind[i], affine_point(m, o), affine_vector(m, d), 0.0, t_max)
        if t < t_max:
            return True
    return False


@kernel
def world_normal(ps, shape, p):
    """Unit outward normal of `shape` at world point p (through the inverse transpose)."""
    m = ps.shape_object_from_world[shape]
    n_object = object_normal(ps.shape_kind[shape], affine_point(m, p))
    return normalize(affine_transpose_vector(m, n_object))


@kernel
def spawn_point(p, n, ray_origin):
    """A start point for rays leaving the surface at p on the side n points to."""
    magnitude = max(max_abs(p), max_abs(ray_origin))
    return add(p, scale(n, SPAWN_OFFSET_RELATIVE * magnitude + SPAWN_OFFSET_ABSOLUTE))
