"""CSG by ray intervals (Roth 1982): union, intersection and difference of any solids.

Along a ray's whole line every operand yields its spans, the sorted parameter intervals
inside it, each end labelled with the surface it crosses: (leaf shape row, part, b1, b2).
A CSG node combines its two operands' span lists in one linear merge, and a program in
postfix order (leaves push their spans, operations pop two lists and push one) evaluates a
tree of any depth without recursion. The nearest surviving boundary past the ray's origin is
the hit. Spans cover the whole line, so a ray that starts inside a solid (a refracted ray,
a shadow ray from a cavity wall) is classified correctly.

Every operand is a row of the shape table with its own world-to-object transform (the
composition of its CSG ancestors' and its own), so no transform is applied twice and an
operand used by several nodes is simply several rows.

Labels: a part is stored as ~part (negative) when the surface faces into the solid, which is
what a subtracted operand's surface does; `surface_at` flips its normal.

Coincident surfaces (a cutter's cap flush with a box face): boundaries of the two operands
closer than a relative tolerance are taken as one event, so the result does not depend on
which of two rounded distances came out smaller. A hole cut flush therefore never keeps a
sliver of skin, on every pixel alike, and on equal footing the left operand's label wins.
"""

import math

from ..jit.decorators import inlined_kernel, kernel
from ..vocabulary import CSG_DIFFERENCE, CSG_INTERSECTION, CSG_UNION
from .mesh_trace import coincident_crossings, line_scale, mesh_line_crossings, sort_crossings
from .shadow_log import SHADOW_VARIES, record_crossing
from .shapes import NO_HIT, SHAPE_MESH, SHAPE_TORUS, convex_interval
from .slabs import box_entry
from .torus import torus_roots
from .vec import affine_point, affine_vector, inverse

# Boundaries of two operands nearer than this, relative to the distances involved, are one
# event (the same relative size as the spawn offset in `trace`)
COINCIDENT_RELATIVE = 1e-9


# Spans of one ray's evaluation (all operands at once), and mesh crossings of one operand;
# a ray that would need more drops the excess and is counted in span_overflow
SPAN_CAPACITY = 512
CROSSING_CAPACITY = 1024


@inlined_kernel
def _put(span_f, span_i, k, end, t, row, part, b1, b2):
    """Write one end (0 enter, 1 exit) of span k."""
    span_f[k, end, 0], span_f[k, end, 1], span_f[k, end, 2] = t, b1, b2
    span_i[k, end, 0], span_i[k, end, 1] = row, part


@inlined_kernel
def _copy_end(span_f, span_i, src, src_end, dst, dst_end):
    for a in range(3):
        span_f[dst, dst_end, a] = span_f[src, src_end, a]
    span_i[dst, dst_end, 0] = span_i[src, src_end, 0]
    span_i[dst, dst_end, 1] = span_i[src, src_end, 1]


@kernel
def _mesh_spans(geo, row, o, d, scratch, at):
    """Spans of a closed mesh along the line: every crossing, sorted, with the winding
    number counted from -inf; inside is where it is not zero, so either orientation works.
    Crossings at the same distance, to rounding (a ray through a shared edge or vertex,
    reported by each triangle there), count once per facing: a ray through an edge between
    two faces facing it enters once; one grazing a silhouette edge enters and leaves, and
    stays outside."""
    span_f, span_i = scratch.span_f, scratch.span_i
    cross_f, cross_i = scratch.cross_f, scratch.cross_i
    n = mesh_line_crossings(
        geo.node_boxes, geo.node_links, geo.tri_corners, geo.mesh_root[geo.shape_index[row]],
        o, d, cross_f, cross_i, scratch.stack,
    )  # fmt: skip
    if n == cross_f.shape[0]:
        scratch.overflow[0] += 1
    sort_crossings(cross_f, cross_i, n)
    scale = line_scale(o, d)
    winding = 0
    k = at
    i = 0
    while i < n:
        t = cross_f[i, 0]
        i, entering, leaving = coincident_crossings(cross_f, cross_i, i, n, scale)
        change = (entering >= 0) - (leaving >= 0)
        if change == 0:
            continue
        c = entering if change > 0 else leaving
        before = winding
        winding += change
        if before == 0:
            if k >= span_f.shape[0]:
                scratch.overflow[0] += 1
                return k
            _put(span_f, span_i, k, 0, t, row, cross_i[c, 0], cross_f[c, 1], cross_f[c, 2])
        elif winding == 0:
            _put(span_f, span_i, k, 1, t, row, cross_i[c, 0], cross_f[c, 1], cross_f[c, 2])
            k += 1
    return k


@inlined_kernel
def operand_spans(geo, row, o, d, inverse_d, scratch, at):
    """Write the spans of shape row `row` along the world line o + t d into the scratch
    lists from position `at`; returns the position after the last. A line that misses the
    operand's world box costs one slab test (inverse_d = 1 / d, per component)."""
    if box_entry(geo.shape_bounds, row, o, inverse_d, -math.inf, math.inf) == NO_HIT:
        return at
    span_f, span_i = scratch.span_f, scratch.span_i
    transforms = geo.shape_object_from_world
    o_obj = affine_point(transforms, row, o)
    d_obj = affine_vector(transforms, row, d)
    kind = geo.shape_kind[row]
    if kind == SHAPE_MESH:
        return _mesh_spans(geo, row, o_obj, d_obj, scratch, at)
    if kind == SHAPE_TORUS:
        n, r0, r1, r2, r3 = torus_roots(
            o_obj, d_obj, geo.shape_param[row, 0], geo.shape_param[row, 1]
        )
        # Crossings pair up as enter, leave; an odd one out is a tangency rounding left alone
        k = at
        for first, second, present in ((r0, r1, n >= 2), (r2, r3, n >= 4)):
            if present:
                if k >= span_f.shape[0]:
                    scratch.overflow[0] += 1
                    return k
                _put(span_f, span_i, k, 0, first, row, 0, 0.0, 0.0)
                _put(span_f, span_i, k, 1, second, row, 0, 0.0, 0.0)
                k += 1
        return k
    t0, p0, t1, p1 = convex_interval(kind, o_obj, d_obj)
    if not t0 < t1:
        return at
    if at >= span_f.shape[0]:
        scratch.overflow[0] += 1
        return at
    _put(span_f, span_i, at, 0, t0, row, p0, 0.0, 0.0)
    _put(span_f, span_i, at, 1, t1, row, p1, 0.0, 0.0)
    return at + 1


@inlined_kernel
def _inside(op, in_a, in_b):
    if op == CSG_UNION:
        return in_a or in_b
    if op == CSG_INTERSECTION:
        return in_a and in_b
    return in_a and not in_b


@inlined_kernel
def combine(op, scratch, a_start, b_start, end, scale):
    """Merge the span lists [a_start, b_start) (left operand) and [b_start, end) (right)
    by `op` into a list starting at a_start; returns its end. One pass over the boundaries
    in order, tracking whether the ray is inside each operand."""
    span_f, span_i = scratch.span_f, scratch.span_i
    # The result is built after `end`, then moved down to a_start
    out = end
    ia, ib = a_start, b_start
    ea = eb = 0  # next end of the current span of each: 0 its entry, 1 its exit
    in_a = in_b = False
    capacity = span_f.shape[0]
    while ia < b_start or ib < end:
        ta = span_f[ia, ea, 0] if ia < b_start else math.inf
        tb = span_f[ib, eb, 0] if ib < end else math.inf
        tolerance = COINCIDENT_RELATIVE * (min(abs(ta), abs(tb)) + scale)
        step_a = ta <= tb + tolerance
        step_b = tb <= ta + tolerance
        before = _inside(op, in_a, in_b)
        if step_a:
            in_a = not in_a
        if step_b:
            in_b = not in_b
        after = _inside(op, in_a, in_b)
        if before != after:
            # Whose surface this is: the left operand's if its step alone changes the
            # result, or if it moved and the right did not
            use_a = step_a and (not step_b or _inside(op, in_a, not in_b) != before)
            src, src_end = (ia, ea) if use_a else (ib, eb)
            dst_end = 1 if before else 0
            if dst_end == 0 and out >= capacity:
                scratch.overflow[0] += 1
                break
            _copy_end(span_f, span_i, src, src_end, out, dst_end)
            # A right operand's surface bounds a difference from inside: it faces inward
            if not use_a and op == CSG_DIFFERENCE:
                span_i[out, dst_end, 1] = ~span_i[out, dst_end, 1]
            if dst_end == 1:
                out += 1
        if step_a:
            ea += 1
            if ea == 2:
                ea, ia = 0, ia + 1
        if step_b:
            eb += 1
            if eb == 2:
                eb, ib = 0, ib + 1
    count = out - end
    for k in range(count):
        for e in range(2):
            _copy_end(span_f, span_i, end + k, e, a_start + k, e)
    return a_start + count


@inlined_kernel
def csg_spans(geo, csg, o, d, scratch):
    """Evaluate CSG program `csg` along the world line o + t d: the number of spans of the
    solid, which are left at the start of the scratch lists. Everything down to the operands'
    spans is inlined, down from `closest_hit` and `transmittance`: a call with the packed
    scene and scratch lists (some twenty arrays) cost 270 ns a ray in reference counting
    alone, five times the spans' own work."""
    program = geo.csg_program
    first, last = geo.csg_range[csg, 0], geo.csg_range[csg, 1]
    segments = scratch.segments
    scale = line_scale(o, d)
    inverse_d = inverse(d)
    pending = 0
    end = 0
    for k in range(first, last):
        step = program[k]
        if step >= 0:
            segments[pending] = end
            pending += 1
            end = operand_spans(geo, step, o, d, inverse_d, scratch, end)
        else:
            pending -= 1
            end = combine(step, scratch, segments[pending - 1], segments[pending], end, scale)
    return end


@inlined_kernel
def csg_closest(geo, csg, o, d, t_max, scratch):
    """Nearest boundary of the CSG solid with 0 < t < t_max: (leaf row, t, part, b1, b2),
    part stored as ~part where the surface faces inward; row -1 when there is none."""
    count = csg_spans(geo, csg, o, d, scratch)
    span_f, span_i = scratch.span_f, scratch.span_i
    for k in range(count):
        for e in range(2):
            t = span_f[k, e, 0]
            if t >= t_max:
                return -1, math.inf, -1, 0.0, 0.0
            if t > 0.0:
                return span_i[k, e, 0], t, span_i[k, e, 1], span_f[k, e, 1], span_f[k, e, 2]
    return -1, math.inf, -1, 0.0, 0.0


@inlined_kernel
def csg_transmittance(geo, csg, o, d, t_max, stacks):
    """The fraction of light passing the CSG solid along 0 < t < t_max, by the shadow rule
    of `trace.transmittance`: each boundary crossed passes its own surface's transparency,
    or is listed for the integrator where that varies (`core.kernels.shadow_log`)."""
    scratch = stacks.csg
    count = csg_spans(geo, csg, o, d, scratch)
    span_f, span_i = scratch.span_f, scratch.span_i
    light = 1.0
    for k in range(count):
        for e in range(2):
            t = span_f[k, e, 0]
            if 0.0 < t < t_max:
                leaf, part = span_i[k, e, 0], span_i[k, e, 1]
                tau = geo.shape_transparency[leaf]
                if tau == SHADOW_VARIES:
                    b1, b2 = span_f[k, e, 1], span_f[k, e, 2]
                    if not record_crossing(stacks, leaf, part, t, b1, b2, o, d):
                        return 0.0
                    continue
                if tau == 0.0:
                    return 0.0
                light *= tau
    return light
