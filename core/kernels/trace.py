"""Rays against the whole scene through the two-level BVH: nearest hit and shadow rays.

The top level is a BVH over the shapes' world-space boxes. At a leaf the ray is carried into
each shape's object space; an analytic shape is solved there, a mesh instance descends into
its own BVH (built once per `TriangleMesh`, shared by all its instances). Traversal is
front-to-back with a fixed-size stack per level (from the `Workspace`), so nearer boxes are
opened first and farther ones skipped once a nearer hit is known.

Boxes are tested with the slab method; the far distance is widened by 2 gamma_3 (Ize 2013)
so that rounding never culls a box a ray truly crosses. Mesh boxes are float32 corners of
float32 vertices, so they are exact; the arithmetic is float64.
"""

from core.jit import kernel
from core.kernels.shapes import NO_HIT, SHAPE_MESH, count_crossings, intersect_analytic
from core.kernels.triangles import intersect_triangle, permuted, shear_setup
from core.kernels.vec import add, affine_point, affine_vector, max_abs, scale

_WIDEN = 1.0 + 6.0 * 2.0**-53

# Secondary rays start this far off the surface, relative to the magnitude of the
# coordinates involved: float64 hit points are accurate to a few ulps of that magnitude, so a
# relative offset stays clear of self-intersection at every scene scale where a fixed epsilon
# fails at one end or the other (Waechter and Binder, Ray Tracing Gems, chapter 6).
SPAWN_OFFSET_RELATIVE = 1e-9
SPAWN_OFFSET_ABSOLUTE = 1e-30


@kernel
def box_entry(bounds, k, o, inv, t_max):
    """Entry distance of the ray into box k of bounds (n, 6) = (lo xyz, hi xyz) within
    [0, t_max]; NO_HIT when it misses. NaNs (a ray in a box's face plane) are ignored."""
    return _slabs(bounds, k, o[0], o[1], o[2], inv[0], inv[1], inv[2], t_max)


@kernel
def _slabs(bounds, k, ox, oy, oz, ix, iy, iz, t_max):
    t_near = 0.0
    t_far = t_max
    t0 = (bounds[k, 0] - ox) * ix
    t1 = (bounds[k, 3] - ox) * ix
    if t0 > t1:
        t0, t1 = t1, t0
    if t0 > t_near:
        t_near = t0
    if t1 < t_far:
        t_far = t1
    t0 = (bounds[k, 1] - oy) * iy
    t1 = (bounds[k, 4] - oy) * iy
    if t0 > t1:
        t0, t1 = t1, t0
    if t0 > t_near:
        t_near = t0
    if t1 < t_far:
        t_far = t1
    t0 = (bounds[k, 2] - oz) * iz
    t1 = (bounds[k, 5] - oz) * iz
    if t0 > t1:
        t0, t1 = t1, t0
    if t0 > t_near:
        t_near = t0
    if t1 < t_far:
        t_far = t1
    if t_near <= t_far * _WIDEN:
        return t_near
    return NO_HIT


@kernel
def _inverse(d):
    return (1.0 / d[0], 1.0 / d[1], 1.0 / d[2])


@kernel
def mesh_closest(bounds, info, tris, vertices, root, o, d, t_max, stack, stack_t):
    """Nearest triangle of the mesh whose BVH starts at node `root`, for a ray in its object
    space: (t, triangle, b1, b2). Takes the arrays it reads rather than the whole packed
    scene: numba passes a tuple argument field by field, and this is called once per ray."""
    ox, oy, oz = o
    ix, iy, iz = _inverse(d)
    shear = shear_setup(d)
    o_sheared = permuted(o, shear)
    best_t, best_tri, best_b1, best_b2 = t_max, -1, 0.0, 0.0
    node = root
    if _slabs(bounds, node, ox, oy, oz, ix, iy, iz, best_t) == NO_HIT:
        return NO_HIT, -1, 0.0, 0.0
    top = 0
    while True:
        count = info[node, 1]
        if count > 0:
            first = info[node, 0]
            for tri in range(first, first + count):
                t, b1, b2 = intersect_triangle(
                    vertices, tris[tri, 0], tris[tri, 1], tris[tri, 2], o_sheared, shear, best_t
                )
                if t < best_t:
                    best_t, best_tri, best_b1, best_b2 = t, tri, b1, b2
        else:
            child = info[node, 0]
            t_left = _slabs(bounds, child, ox, oy, oz, ix, iy, iz, best_t)
            t_right = _slabs(bounds, child + 1, ox, oy, oz, ix, iy, iz, best_t)
            if t_left != NO_HIT:
                if t_right != NO_HIT:
                    if t_right < t_left:
                        stack[top] = child
                        stack_t[top] = t_left
                        node = child + 1
                    else:
                        stack[top] = child + 1
                        stack_t[top] = t_right
                        node = child
                    top += 1
                    continue
                node = child
                continue
            if t_right != NO_HIT:
                node = child + 1
                continue
        # Pop the nearest waiting node that could still hold a nearer hit
        while top > 0:
            top -= 1
            if stack_t[top] < best_t:
                break
        else:
            break
        node = stack[top]
    if best_tri < 0:
        return NO_HIT, -1, 0.0, 0.0
    return best_t, best_tri, best_b1, best_b2


@kernel
def mesh_crossings(ps, mesh, o, d, t_max, stop_at_first, stack):
    """How many triangles of `mesh` the segment crosses (stopping at 1 if stop_at_first)."""
    inv = _inverse(d)
    shear = shear_setup(d)
    o_sheared = permuted(o, shear)
    bounds, info, tris = ps.node_bounds, ps.node_info, ps.tri_vertices
    crossings = 0
    stack[0] = ps.mesh_root[mesh]
    top = 1
    while top > 0:
        top -= 1
        node = stack[top]
        if box_entry(bounds, node, o, inv, t_max) == NO_HIT:
            continue
        count = info[node, 1]
        if count == 0:
            stack[top] = info[node, 0]
            stack[top + 1] = info[node, 0] + 1
            top += 2
            continue
        first = info[node, 0]
        for tri in range(first, first + count):
            t, _, _ = intersect_triangle(
                ps.vertices, tris[tri, 0], tris[tri, 1], tris[tri, 2], o_sheared, shear, t_max
            )
            if t < t_max:
                crossings += 1
                if stop_at_first:
                    return crossings
    return crossings


@kernel
def closest_hit(ps, o, d, t_max, ws):
    """Nearest hit along o + t d with 0 < t < t_max: (shape, t, part, b1, b2).

    part is the surface part for analytic shapes, the triangle for meshes; b1 and b2 are
    barycentric weights on meshes. A miss returns (-1, NO_HIT, -1, 0, 0)."""
    stack, stack_t = ws.top_stack, ws.top_stack_t
    ox, oy, oz = o
    ix, iy, iz = _inverse(d)
    bounds, info = ps.top_bounds, ps.top_info
    # Scalars, not a tuple, carry the best hit through the loop: numba keeps them in
    # registers (a reassigned mixed-type tuple here cost half the mesh traversal's speed)
    best_shape, best_t, best_part, best_b1, best_b2 = -1, t_max, -1, 0.0, 0.0
    if info.shape[0] == 0 or _slabs(bounds, 0, ox, oy, oz, ix, iy, iz, t_max) == NO_HIT:
        return -1, NO_HIT, -1, 0.0, 0.0
    node = 0
    top = 0
    while True:
        count = info[node, 1]
        if count > 0:
            first = info[node, 0]
            for k in range(first, first + count):
                shape = ps.top_order[k]
                m = ps.shape_object_from_world[shape]
                o_obj, d_obj = affine_point(m, o), affine_vector(m, d)
                kind = ps.shape_kind[shape]
                if kind == SHAPE_MESH:
                    t, part, b1, b2 = mesh_closest(
                        ps.node_bounds,
                        ps.node_info,
                        ps.tri_vertices,
                        ps.vertices,
                        ps.mesh_root[ps.shape_mesh[shape]],
                        o_obj,
                        d_obj,
                        best_t,
                        ws.stack,
                        ws.stack_t,
                    )
                else:
                    major, minor = ps.shape_param[shape, 0], ps.shape_param[shape, 1]
                    t, part = intersect_analytic(kind, major, minor, o_obj, d_obj, 0.0, best_t)
                    b1 = b2 = 0.0
                if t < best_t:
                    best_shape, best_t, best_part, best_b1, best_b2 = shape, t, part, b1, b2
        else:
            child = info[node, 0]
            t_left = _slabs(bounds, child, ox, oy, oz, ix, iy, iz, best_t)
            t_right = _slabs(bounds, child + 1, ox, oy, oz, ix, iy, iz, best_t)
            if t_left != NO_HIT:
                if t_right != NO_HIT:
                    if t_right < t_left:
                        stack[top] = child
                        stack_t[top] = t_left
                        node = child + 1
                    else:
                        stack[top] = child + 1
                        stack_t[top] = t_right
                        node = child
                    top += 1
                    continue
                node = child
                continue
            if t_right != NO_HIT:
                node = child + 1
                continue
        while top > 0:
            top -= 1
            if stack_t[top] < best_t:
                break
        else:
            break
        node = stack[top]
    if best_shape < 0:
        return -1, NO_HIT, -1, 0.0, 0.0
    return best_shape, best_t, best_part, best_b1, best_b2


@kernel
def transmittance(ps, o, d, t_max, ws):
    """The fraction of light that passes along o + t d, 0 < t < t_max (shadow rays).

    The rule for transparent objects: each crossing of a surface whose material has
    transparency tau multiplies the light by tau, without bending or Fresnel loss (a shadow
    ray cannot follow refraction to the light). Opaque surfaces (tau = 0) block it outright,
    and the search stops at the first of them, as an any-hit query."""
    stack = ws.top_stack
    if ps.top_info.shape[0] == 0:
        return 1.0
    inv = _inverse(d)
    light = 1.0
    stack[0] = 0
    top = 1
    while top > 0:
        top -= 1
        node = stack[top]
        if box_entry(ps.top_bounds, node, o, inv, t_max) == NO_HIT:
            continue
        count = ps.top_info[node, 1]
        if count == 0:
            stack[top] = ps.top_info[node, 0]
            stack[top + 1] = ps.top_info[node, 0] + 1
            top += 2
            continue
        first = ps.top_info[node, 0]
        for k in range(first, first + count):
            shape = ps.top_order[k]
            tau = ps.material_transparency[ps.shape_material[shape]]
            m = ps.shape_object_from_world[shape]
            o_obj, d_obj = affine_point(m, o), affine_vector(m, d)
            kind = ps.shape_kind[shape]
            if kind == SHAPE_MESH:
                crossings = mesh_crossings(
                    ps, ps.shape_mesh[shape], o_obj, d_obj, t_max, tau == 0.0, ws.stack
                )
            else:
                major, minor = ps.shape_param[shape, 0], ps.shape_param[shape, 1]
                crossings = count_crossings(kind, major, minor, o_obj, d_obj, 0.0, t_max)
            if crossings > 0:
                if tau == 0.0:
                    return 0.0
                light *= tau**crossings
    return light


@kernel
def spawn_point(p, n, ray_origin):
    """A start point for rays leaving the surface at p on the side n points to."""
    magnitude = max(max_abs(p), max_abs(ray_origin))
    return add(p, scale(n, SPAWN_OFFSET_RELATIVE * magnitude + SPAWN_OFFSET_ABSOLUTE))
