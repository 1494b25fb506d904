"""Rays against one mesh's eight-wide BVH, in the mesh's object space, by two traversals:
the nearest triangle (`mesh_closest`), and the crossings of a segment or of a whole line
(`mesh_crossings`: counted for shadow rays, listed for CSG).

See `core.kernels.bvh_wide` for the node layout, `core.kernels.slabs` for its float32 slab
test, and `core.kernels.triangles` for the leaf blocks and the watertight triangle test. Each
traversal keeps its own fixed-size stack (`MESH_STACK_SIZE`), indexed as unsigned so that
numba does not emit its negative-index wraparound on every push and pop.

A node's eight children are pushed by eight straight-line calls rather than a loop: numba
compiles a loop over a tuple of eight into a jump table, and its indirect branches cost more
than the whole slab test.
"""

import math

import numpy as np

from ..jit.decorators import inlined_kernel, kernel
from .bvh_wide import leaf_block as _leaf_block
from .prefetch import prefetch_row
from .shapes import NO_HIT
from .slabs import INF32, child_entries, float32_above, float32_below, slab_ray, widened32
from .triangles import (
    FACING_SIGN,
    LEAF_WIDTH,
    barycentrics,
    intersect_leaf,
    permuted,
    shear_setup,
    slot_of,
)

# Crossings of one mesh closer than this, relative to the size of the distances involved, are
# one event: the distances two triangles compute for a point of their shared edge differ by
# rounding (a few units in the last place: 38.67452487468917 and ...16 for one edge), and
# counted apart, a ray through that edge entered twice and the solid lost its span. Far
# finer than any two surfaces a scene could tell apart
MESH_COINCIDENT_RELATIVE = 1e-12


ZERO32 = np.float32(0.0)


@inlined_kernel
def _ray_constants(o, d, whole_line):
    """What a traversal computes once per ray: the float32 slab test's `SlabRay`, the
    triangle test's shear and the origin in the shear's order."""
    shear = shear_setup(d)
    return slab_ray(o, d, whole_line), shear, permuted(o, shear)


@inlined_kernel
def _push_by_distance(stack, stack_t, top, base, links, node, c, t, boxes, corners):
    """Put child c of `node` (entered at t; INF32 if missed, then nothing happens) among the
    entries stack[base:top], which are kept farthest first, so that the nearest is popped
    first, and prefetch what it names. Returns the new top."""
    if t == INF32:
        return top
    j = top
    while j > base and stack_t[np.uintp(j - 1)] < t:
        below = np.uintp(j - 1)
        stack[np.uintp(j)], stack_t[np.uintp(j)] = stack[below], stack_t[below]
        j -= 1
    child = links[node, c]
    stack[np.uintp(j)], stack_t[np.uintp(j)] = child, t
    if child >= 0:
        prefetch_row(boxes, child)
        prefetch_row(links, child)
    else:
        prefetch_row(corners, _leaf_block(child))
    return top + 1


@inlined_kernel
def _push(stack, top, links, node, c, t):
    """Push child c of `node` if the ray enters it (t < INF32). Returns the new top."""
    if t == INF32:
        return top
    stack[np.uintp(top)] = links[node, c]
    return top + 1


@inlined_kernel
def _push_all(stack, top, links, node, e):
    """`_push` for the eight children of `node`, entry distances e."""
    top = _push(stack, top, links, node, 0, e[0])
    top = _push(stack, top, links, node, 1, e[1])
    top = _push(stack, top, links, node, 2, e[2])
    top = _push(stack, top, links, node, 3, e[3])
    top = _push(stack, top, links, node, 4, e[4])
    top = _push(stack, top, links, node, 5, e[5])
    top = _push(stack, top, links, node, 6, e[6])
    return _push(stack, top, links, node, 7, e[7])


@inlined_kernel
def mesh_closest(boxes, links, corners, root, o, d, t_max, stack, stack_t):
    """Nearest triangle of the mesh whose BVH starts at node `root`, for a ray in its object
    space: (t, triangle slot, b1, b2). Children are visited nearest first: those a ray
    enters go onto the stack sorted by entry distance. Inlined into `closest_hit`:
    measured 8% more primary rays per second than a call."""
    ray, shear, o_sheared = _ray_constants(o, d, False)
    best_t, best_tri, best_v, best_w, best_det = t_max, -1, 0.0, 0.0, 1.0
    # The float32 bound the slab test clips to, and the entry distance past which a waiting
    # box cannot hold a nearer hit: an entry distance may exceed the exact one by the slab
    # test's rounding, which `widened32` covers
    best32 = float32_above(t_max)
    cull32 = widened32(best32)
    stack[0], stack_t[0] = root, ZERO32
    top = 1
    while top > 0:
        top -= 1
        link = stack[np.uintp(top)]
        if stack_t[np.uintp(top)] > cull32:
            continue
        if link < 0:
            block = _leaf_block(link)
            hits = intersect_leaf(corners, block, o_sheared, shear, 0.0, best_t)
            for k in range(LEAF_WIDTH):
                t, v, w, det = hits[k]
                if t < best_t:
                    best_t, best_tri, best_v, best_w, best_det = t, slot_of(block, k), v, w, det
            best32 = float32_above(best_t)
            cull32 = widened32(best32)
            continue
        e = child_entries(boxes, link, ray, ZERO32, best32)
        base = top
        top = _push_by_distance(stack, stack_t, top, base, links, link, 0, e[0], boxes, corners)
        top = _push_by_distance(stack, stack_t, top, base, links, link, 1, e[1], boxes, corners)
        top = _push_by_distance(stack, stack_t, top, base, links, link, 2, e[2], boxes, corners)
        top = _push_by_distance(stack, stack_t, top, base, links, link, 3, e[3], boxes, corners)
        top = _push_by_distance(stack, stack_t, top, base, links, link, 4, e[4], boxes, corners)
        top = _push_by_distance(stack, stack_t, top, base, links, link, 5, e[5], boxes, corners)
        top = _push_by_distance(stack, stack_t, top, base, links, link, 6, e[6], boxes, corners)
        top = _push_by_distance(stack, stack_t, top, base, links, link, 7, e[7], boxes, corners)
    if best_tri < 0:
        return NO_HIT, -1, 0.0, 0.0
    b1, b2 = barycentrics(best_v, best_w, best_det)
    return best_t, best_tri, b1, b2


@inlined_kernel
def mesh_crossings(boxes, links, corners, root, o, d, t_min, t_max, stop_at_first, cross_f,
                   cross_i, stack):  # fmt: skip
    """The crossings of o + t d, t_min < t < t_max, with the mesh whose BVH starts at `root`:
    the one traversal for queries that want every crossing, not the nearest. Children are
    pushed in slot order, unsorted: for a query that stops at any blocker, sorting by
    distance cost more than it found sooner.

    With cross_f None (a shadow ray's segment) the crossings are only counted, stopping at 1
    if stop_at_first. Otherwise (CSG: the whole line, t from -inf to inf) they are listed,
    unsorted and at most the lists' length: cross_f[k] = (t, b1, b2), cross_i[k] = (triangle
    slot, +1 where the line enters through the triangle's front, -1 where it leaves).
    numba compiles each form on its own, the branch on None taken at compile time. Returns
    the count."""
    # A negative t_min is a whole line's query (the slab test treats those apart)
    ray, shear, o_sheared = _ray_constants(o, d, t_min < 0.0)
    t_min32, t_max32 = float32_below(t_min), float32_above(t_max)
    count = 0
    stack[0] = root
    top = 1
    while top > 0:
        top -= 1
        link = stack[np.uintp(top)]
        if link < 0:
            block = _leaf_block(link)
            hits = intersect_leaf(corners, block, o_sheared, shear, t_min, t_max)
            if cross_f is None:
                # Counted without a branch per lane: four branches cost 15% of a shadow ray
                crossed = (
                    (hits[0][0] < t_max) + (hits[1][0] < t_max)
                    + (hits[2][0] < t_max) + (hits[3][0] < t_max)
                )  # fmt: skip
                count += crossed
                if stop_at_first and crossed > 0:
                    return count
            else:
                count = _list_crossings(hits, block, t_max, cross_f, cross_i, count)
            continue
        e = child_entries(boxes, link, ray, t_min32, t_max32)
        top = _push_all(stack, top, links, link, e)
    return count


@inlined_kernel
def _list_crossings(hits, block, t_max, cross_f, cross_i, count):
    """Append the hits of leaf block `block` to the crossing lists (see `mesh_crossings`)
    while they have room; returns the new count."""
    for k in range(LEAF_WIDTH):
        t, v, w, det = hits[k]
        if t < t_max and count < cross_f.shape[0]:
            b1, b2 = barycentrics(v, w, det)
            cross_f[count, 0], cross_f[count, 1], cross_f[count, 2] = t, b1, b2
            cross_i[count, 0] = slot_of(block, k)
            cross_i[count, 1] = 1 if FACING_SIGN * det > 0.0 else -1
            count += 1
    return count


@kernel
def mesh_line_crossings(boxes, links, corners, root, o, d, cross_f, cross_i, stack):
    """Every crossing of the whole line o + t d with the mesh (`mesh_crossings`' listing
    form), compiled once as a call of its own for the CSG kernels."""
    return mesh_crossings(
        boxes, links, corners, root, o, d, -math.inf, math.inf, False, cross_f, cross_i, stack
    )


@kernel
def sort_crossings(cross_f, cross_i, n):
    """Sort the first n crossings by t, in place: Shell sort with Ciura's gaps, so that a
    mesh crossed a thousand times costs some 10^4 steps, not the 10^6 of insertion sort."""
    for gap in (701, 301, 132, 57, 23, 10, 4, 1):
        for i in range(gap, n):
            t, b1, b2 = cross_f[i, 0], cross_f[i, 1], cross_f[i, 2]
            tri, sign = cross_i[i, 0], cross_i[i, 1]
            j = i
            while j >= gap and cross_f[j - gap, 0] > t:
                for a in range(3):
                    cross_f[j, a] = cross_f[j - gap, a]
                cross_i[j, 0], cross_i[j, 1] = cross_i[j - gap, 0], cross_i[j - gap, 1]
                j -= gap
            cross_f[j, 0], cross_f[j, 1], cross_f[j, 2] = t, b1, b2
            cross_i[j, 0], cross_i[j, 1] = tri, sign


@kernel
def mesh_surface_crossings(boxes, links, corners, root, o, d, t_max, cross_f, cross_i, stack):
    """How many times o + t d, 0 < t < t_max, crosses the mesh's surface, for a shadow ray
    through a surface that lets light through: crossings listed, sorted and merged as the
    CSG kernels merge them, so that a ray through an edge or vertex shared by triangles
    facing the same way crosses once, not once per triangle (a transparent card passed
    tau^2 along its diagonal). The merged crossings are left at the start of the lists, in
    order (core.kernels.shadow_log reads them); -1 when they do not all fit."""
    count = mesh_crossings(boxes, links, corners, root, o, d, 0.0, t_max, False, cross_f,
                           cross_i, stack)  # fmt: skip
    if count >= cross_f.shape[0]:
        return -1
    sort_crossings(cross_f, cross_i, count)
    scale = line_scale(o, d)
    events = 0
    i = 0
    while i < count:
        i, entering, leaving = coincident_crossings(cross_f, cross_i, i, count, scale)
        # in index order, each kept row moves to or before where it was (events <= i)
        if entering > leaving:
            entering, leaving = leaving, entering
        for c in (entering, leaving):
            if c >= 0:
                _copy_crossing(cross_f, cross_i, c, events)
                events += 1
    return events


@inlined_kernel
def _copy_crossing(cross_f, cross_i, src, dst):
    for a in range(3):
        cross_f[dst, a] = cross_f[src, a]
    cross_i[dst, 0], cross_i[dst, 1] = cross_i[src, 0], cross_i[src, 1]


@inlined_kernel
def line_scale(o, d):
    """The size of the distances along o + t d that rounding is relative to."""
    return max(abs(o[0]), abs(o[1]), abs(o[2])) / math.sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2])


@inlined_kernel
def coincident_crossings(cross_f, cross_i, i, n, scale):
    """The sorted crossings from i on at its distance, to rounding (MESH_COINCIDENT_RELATIVE
    of `scale`): one event, a ray through an edge or vertex that each triangle there
    reported. Returns (the crossing after them, the last of them entering or -1, the last
    leaving or -1)."""
    same = cross_f[i, 0] + MESH_COINCIDENT_RELATIVE * (abs(cross_f[i, 0]) + scale)
    entering = leaving = -1
    while i < n and cross_f[i, 0] <= same:
        if cross_i[i, 1] > 0:
            entering = i
        else:
            leaving = i
        i += 1
    return i, entering, leaving
