"""An emissive surface lighting the scene (core.compile.glowing): a point picked on its
triangles in proportion to their area, both sides emitting (as Cycles' emission does).

For a shading point at x and a point y on the surface, at distance d along unit L, the
sample's weight is A |n.L| / d^2 (A the surface's whole area, n the triangle's normal): with
the table's radiance L_e / pi (core.kernels.emitters) a white Lambertian point gets
E / pi, E the irradiance from the surface, as Cycles lights it.

A surface whose emission varies has each triangle cut into level x level sub-triangles of
their own radiance L_k (core.kernels.glow_bake), picked in proportion to area A_k times
strength s_k (L_k's mean; _sub_triangle): A is then sum A_k s_k, the table's radiance 1 / pi,
and each sample's tint L_k / s_k gives it its own radiance. A constant emitter has level 1,
tint 1 and strength 1."""

import math

from ..jit.decorators import kernel
from .vec import add, cross, dot, row, scale, sub

# The shadow ray stops this fraction short of the sampled point, which lies on the surface
# it must not be blocked by
SHORT_OF_SURFACE = 1e-7
# Lights.glow_cdf's columns (core.compile.glowing): each sub-triangle's running share within
# its row of the grid, each row's within its triangle, each triangle's within its emitter
SUB_SHARES, ROW_SHARES, TRIANGLE_SHARES = 0, 1, 2


@kernel
def _corner(triangles, k, first):
    return triangles[k, first], triangles[k, first + 1], triangles[k, first + 2]


@kernel
def _pick(cdf, column, first, count, a):
    """The row of cdf[first : first + count, column] (running shares, the last 1) that a in
    [0, 1) falls in (a binary search), and a rescaled to [0, 1) within it, so that
    stratified samples stay stratified."""
    lo, hi = first, first + count - 1
    while lo < hi:
        mid = (lo + hi) // 2
        if cdf[mid, column] <= a:
            lo = mid + 1
        else:
            hi = mid
    below = cdf[lo - 1, column] if lo > first else 0.0
    share = cdf[lo, column] - below
    return lo, min(max((a - below) / share, 0.0), 1.0 - 1e-12) if share > 0.0 else 0.5


@kernel
def _sub_triangle(lights, light, a, b):
    """(sub-triangle row, a, b rescaled within it) of sample (a, b): a picks the triangle,
    then the row of sub-triangles within it, b the sub-triangle in that row, by the running
    shares of core.compile.glowing's three columns. Inverting a piecewise constant density
    in two dimensions so keeps a stratified square's samples spread over the surface, where
    picking among the sub-triangles by a alone would bunch them."""
    param, cdf = lights.emitter_param, lights.glow_cdf
    first, count, level = int(param[light, 0]), int(param[light, 1]), int(param[light, 3])
    t, a = _pick(cdf, TRIANGLE_SHARES, first, count, a)
    local = t - first
    i, a = _pick(cdf, ROW_SHARES, first + local * level, level, a)
    r = i - first - local * level
    # row r of a triangle's grid holds 2 (level - r) - 1 sub-triangles, after r (2 level - r)
    row_first = first + local * level * level + r * (2 * level - r)
    k, b = _pick(cdf, SUB_SHARES, row_first, 2 * (level - r) - 1, b)
    return k, a, b


@kernel
def mesh_sample(lights, light, origin, a, b):
    """(unit direction, distance, weight, RGB tint) of sample (a, b) of emissive surface
    `light`."""
    k, a, b = _sub_triangle(lights, light, a, b)
    area = lights.emitter_param[light, 2]
    triangles = lights.glow_triangles
    v0, v1, v2 = _corner(triangles, k, 0), _corner(triangles, k, 3), _corner(triangles, k, 6)
    # A uniform point of the triangle: the square mapped by (1 - sqrt a, b sqrt a), which
    # keeps neighbouring samples together (folding the square keeps them less so)
    root = math.sqrt(a)
    y = add(v0, add(scale(sub(v1, v0), 1.0 - root), scale(sub(v2, v0), b * root)))
    to_light = sub(y, origin)
    distance = math.sqrt(dot(to_light, to_light))
    tint = row(lights.glow_tint, k)
    if distance == 0.0:
        return (0.0, 0.0, 1.0), 0.0, 0.0, tint
    direction = scale(to_light, 1.0 / distance)
    n = cross(sub(v1, v0), sub(v2, v0))
    length = math.sqrt(dot(n, n))
    if length == 0.0:
        return direction, 0.0, 0.0, tint
    cos_light = abs(dot(n, direction)) / length
    weight = area * cos_light / (distance * distance)
    return direction, distance, weight, tint
