"""An emissive surface lighting the scene (core.compile.glowing): a point picked on its
triangles in proportion to their area, both sides emitting (as Cycles' emission does).

For a shading point at x and a point y on the surface, at distance d along unit L, the
sample's weight is A |n.L| / d^2 (A the surface's whole area, n the triangle's normal): with
the table's radiance L_e / pi (core.kernels.emitters) a white Lambertian point gets
E / pi, E the irradiance from the surface, as Cycles lights it."""

import math

from ..jit.decorators import kernel
from .vec import add, cross, dot, scale, sub

# The shadow ray stops this fraction short of the sampled point, which lies on the surface
# it must not be blocked by
SHORT_OF_SURFACE = 1e-7


@kernel
def _corner(triangles, k, first):
    return triangles[k, first], triangles[k, first + 1], triangles[k, first + 2]


@kernel
def _pick(cdf, first, count, a):
    """The triangle a in [0, 1) falls in (binary search over the running shares), and a
    rescaled to [0, 1) within it, so that stratified samples stay stratified."""
    lo, hi = first, first + count - 1
    while lo < hi:
        mid = (lo + hi) // 2
        if cdf[mid] <= a:
            lo = mid + 1
        else:
            hi = mid
    below = cdf[lo - 1] if lo > first else 0.0
    share = cdf[lo] - below
    return lo, min(max((a - below) / share, 0.0), 1.0 - 1e-12) if share > 0.0 else 0.5


@kernel
def mesh_sample(lights, light, origin, a, b):
    """(unit direction, distance, weight) of sample (a, b) of emissive surface `light`."""
    param = lights.emitter_param
    first, count, area = int(param[light, 0]), int(param[light, 1]), param[light, 2]
    k, a = _pick(lights.glow_cdf, first, count, a)
    triangles = lights.glow_triangles
    v0, v1, v2 = _corner(triangles, k, 0), _corner(triangles, k, 3), _corner(triangles, k, 6)
    # A uniform point of the triangle: the square mapped by (1 - sqrt a, b sqrt a), which
    # keeps neighbouring samples together (folding the square keeps them less so)
    root = math.sqrt(a)
    y = add(v0, add(scale(sub(v1, v0), 1.0 - root), scale(sub(v2, v0), b * root)))
    to_light = sub(y, origin)
    distance = math.sqrt(dot(to_light, to_light))
    if distance == 0.0:
        return (0.0, 0.0, 1.0), 0.0, 0.0
    direction = scale(to_light, 1.0 / distance)
    n = cross(sub(v1, v0), sub(v2, v0))
    length = math.sqrt(dot(n, n))
    if length == 0.0:
        return direction, 0.0, 0.0
    cos_light = abs(dot(n, direction)) / length
    weight = area * cos_light / (distance * distance)
    return direction, distance, weight
