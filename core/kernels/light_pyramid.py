"""Which shapes can shade a point from an area light: the light's pyramid, culled once per point.

Every shadow ray from a shading point to an area light runs from the point O to some point of
the light's rectangle, so all of them lie in the pyramid with apex O over that rectangle (the
convex hull of O and the four corners). A shape whose world box misses the pyramid cannot
stop any of them. `pyramid_candidates` walks the top-level BVH once per shading point and
light with the pyramid instead of a ray and lists the shapes whose boxes meet it; the N
shadow rays then test those alone (`core.kernels.trace.transmittance`), and a point whose
list is empty is lit with no ray test at all. The answer is exactly what testing every
shape would give: only shapes no ray can hit are left out.

The test is conservative, as box culling must be: a box is dropped only when it lies wholly
outside the pyramid's bounding box or wholly outside one of its five face planes, each
pushed out by a margin far above the rounding of the rays' own arithmetic. Boxes near the
pyramid's edges may be kept although they miss it (the separating axes of edge pairs are not
tried); that costs only box tests per ray. A pyramid too thin for its planes to be
trusted (a point in the light's own plane) is culled by its bounding box alone.

The pyramid is packed into a (PYRAMID_ROWS, 4) array: five planes (normal, offset; a box
with min over its corners of normal . x > offset is outside), then its bounding box.
"""

import math

from ..jit.decorators import kernel
from .vec import add, cross, dot, max_abs, scale, sub

# Rays are computed to a few ulps of the coordinates involved; the margin is far above that
# and far below any size a scene cares about (the same relative size as the spawn offset)
PYRAMID_MARGIN_RELATIVE = 1e-9
PYRAMID_ROWS = 7  # 5 planes, then the bounding box's low and high corners
# Shapes listed per shading point and light; a pyramid holding more is traced as usual
MAX_CANDIDATES = 32
# `pyramid_candidates` returns this when the list would overflow: test every shape
TRAVERSE_ALL = -1


@kernel
def _put_plane(pyramid, i, normal, through, inside, margin):
    """Plane i of the pyramid: through `through` with `normal` turned away from `inside`,
    pushed out by `margin`. A plane the inside point nearly lies on is too thin to trust:
    it is left out (a zero normal never culls)."""
    length = math.sqrt(dot(normal, normal))
    depth = dot(normal, sub(inside, through))
    if length == 0.0 or abs(depth) <= 2.0 * margin * length:
        for a in range(4):
            pyramid[i, a] = 0.0
        return
    if depth > 0.0:
        normal = scale(normal, -1.0)
    pyramid[i, 0], pyramid[i, 1], pyramid[i, 2] = normal
    pyramid[i, 3] = dot(normal, through) + margin * length


@kernel
def build_pyramid(pyramid, apex, centre, edge_u, edge_v):
    """Fill `pyramid` with the hull of `apex` and the rectangle centre +- edge_u/2 +- edge_v/2."""
    half_u, half_v = scale(edge_u, 0.5), scale(edge_v, 0.5)
    c0 = sub(sub(centre, half_u), half_v)
    c1 = sub(add(centre, half_u), half_v)
    c2 = add(add(centre, half_u), half_v)
    c3 = add(sub(centre, half_u), half_v)
    reach = max(max_abs(apex), max_abs(centre) + max_abs(half_u) + max_abs(half_v))
    margin = PYRAMID_MARGIN_RELATIVE * reach
    inside = add(scale(apex, 0.2), scale(centre, 0.8))
    _put_plane(pyramid, 0, cross(sub(c0, apex), sub(c1, apex)), apex, inside, margin)
    _put_plane(pyramid, 1, cross(sub(c1, apex), sub(c2, apex)), apex, inside, margin)
    _put_plane(pyramid, 2, cross(sub(c2, apex), sub(c3, apex)), apex, inside, margin)
    _put_plane(pyramid, 3, cross(sub(c3, apex), sub(c0, apex)), apex, inside, margin)
    _put_plane(pyramid, 4, cross(edge_u, edge_v), centre, inside, margin)
    for a in range(3):
        lo = min(apex[a], c0[a], c1[a], c2[a], c3[a])
        hi = max(apex[a], c0[a], c1[a], c2[a], c3[a])
        pyramid[5, a] = lo - margin
        pyramid[6, a] = hi + margin


@kernel
def box_meets_pyramid(pyramid, bounds, k):
    """False when box k of bounds (n, 6+: lo xyz, hi xyz) lies wholly outside the pyramid's
    bounding box or one of its planes; True otherwise (it may meet the pyramid)."""
    for a in range(3):
        if bounds[k, a] > pyramid[6, a] or bounds[k, 3 + a] < pyramid[5, a]:
            return False
    for i in range(5):
        nearest = 0.0
        for a in range(3):
            n = pyramid[i, a]
            nearest += n * (bounds[k, a] if n > 0.0 else bounds[k, 3 + a])
        if nearest > pyramid[i, 3]:
            return False
    return True


@kernel
def pyramid_candidates(geo, pyramid, candidates, stack):
    """List in `candidates`, in leaf order, the scene's shapes whose world boxes may meet
    the pyramid; returns how many, or TRAVERSE_ALL if more than the list holds. Leaf order
    (left subtree first) is the order `transmittance` meets shapes in, so both multiply
    transparencies in the same order and give the same bits."""
    bounds, info, order = geo.top_bounds, geo.top_info, geo.top_order
    if info.shape[0] == 0 or not box_meets_pyramid(pyramid, bounds, 0):
        return 0
    count = 0
    capacity = candidates.shape[0]
    node = 0
    top = 0
    while True:
        first, leaf_count = info[node, 0], info[node, 1]
        if leaf_count > 0:
            for k in range(first, first + leaf_count):
                shape = order[k]
                # A shape that lets all light through (casts no shadow) needs no test
                if geo.shape_transparency[shape] == 1.0:
                    continue
                if box_meets_pyramid(pyramid, geo.shape_bounds, shape):
                    if count == capacity:
                        return TRAVERSE_ALL
                    candidates[count] = shape
                    count += 1
            node = -1
        else:
            left = box_meets_pyramid(pyramid, bounds, first)
            right = box_meets_pyramid(pyramid, bounds, first + 1)
            if left and right:
                stack[top] = first + 1
                top += 1
            node = first if left else (first + 1 if right else -1)
        if node < 0:
            if top == 0:
                return count
            top -= 1
            node = stack[top]
