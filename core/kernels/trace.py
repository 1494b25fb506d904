"""Rays against the whole scene through the two-level BVH: nearest hit and shadow rays.

The top level is a BVH over the shapes' world-space boxes. At a leaf the ray is carried into
each shape's object space; an analytic shape is solved there, a mesh instance descends into
its own BVH (built once per `TriangleMesh`, shared by all its instances). Nearest-hit
traversal is front-to-back with a fixed-size stack per level (from the `Workspace`), so nearer
boxes are opened first and farther ones skipped once a nearer hit is known. Shadow rays walk
the top level in leaf order instead (left child first), so that the transparencies they
multiply come in one fixed order, the order an area light's candidate list keeps too.

Boxes are tested with the float64 slab test of `core.kernels.slabs`, which never culls a box
a ray truly crosses. Mesh BVHs are eight wide (`core.kernels.bvh_wide`); their boxes are
float32 corners of float32 vertices, padded one float32 step, and tested in float32.
"""

from ..jit.decorators import inlined_kernel, kernel, optimised_alone
from .csg import csg_closest, csg_transmittance
from .mesh_trace import mesh_closest, mesh_crossings, mesh_surface_crossings
from .shadow_log import SHADOW_VARIES, analytic_varying, mesh_varying
from .shapes import (
    NO_HIT,
    SHAPE_CSG,
    SHAPE_MESH,
    count_crossings,
    intersect_analytic,
)
from .slabs import box_entry, widened
from .vec import add, affine_point, affine_vector, inverse, max_abs, scale
from .workspace import OCCLUDER_POSITION, OCCLUDER_SHAPE

# Secondary rays start this far off the surface, relative to the magnitude of the
# coordinates involved: float64 hit points are accurate to a few ulps of that magnitude, so a
# relative offset stays clear of self-intersection at every scene scale where a fixed epsilon
# fails at one end or the other (Waechter and Binder, Ray Tracing Gems, chapter 6).
SPAWN_OFFSET_RELATIVE = 1e-9
SPAWN_OFFSET_ABSOLUTE = 1e-30


@inlined_kernel
def descend(bounds, child, o, inverse_d, t_max, stack, stack_t, top):
    """One step down from an inner node whose children are `child` and `child + 1`: test
    both boxes, go on to the nearer one hit and push the other if it is hit too.
    Returns (next node or -1 if neither is hit, new stack top)."""
    t_left = box_entry(bounds, child, o, inverse_d, 0.0, t_max)
    t_right = box_entry(bounds, child + 1, o, inverse_d, 0.0, t_max)
    if t_left == NO_HIT:
        return (child + 1 if t_right != NO_HIT else -1), top
    if t_right == NO_HIT:
        return child, top
    if t_right < t_left:
        stack[top], stack_t[top] = child, t_left
        return child + 1, top + 1
    stack[top], stack_t[top] = child + 1, t_right
    return child, top + 1


@inlined_kernel
def pop_nearer(stack, stack_t, top, t_max):
    """The next waiting node that could still hold a hit nearer than t_max:
    (node or -1 when none is left, new stack top). A node's entry distance may exceed the
    exact one by the slab test's rounding, which `widened` covers."""
    while top > 0:
        top -= 1
        if stack_t[top] <= widened(t_max):
            return stack[top], top
    return -1, 0


@optimised_alone
@inlined_kernel
def closest_hit(geo, o, d, t_max, stacks):
    """Nearest hit along o + t d with 0 < t < t_max: (shape, t, part, b1, b2).

    part is the surface part for analytic shapes, the triangle for meshes; b1 and b2 are
    barycentric weights on meshes. On a CSG solid, shape is the operand's row and part is
    stored as ~part where the surface faces into the solid (see `core.kernels.csg`). A miss
    returns (-1, NO_HIT, -1, 0, 0). Inlined into its
    two callers (the integrator and the batch entry point): a call passes every array of
    `geo` and `stacks` field by field, which cost 60 ns a ray, 20% of a primary ray's time
    against the million-triangle mesh."""
    stack, stack_t, mesh_stack, mesh_stack_t = stacks.top, stacks.top_t, stacks.mesh, stacks.mesh_t
    scratch = stacks.csg
    bounds, info, order = geo.top_bounds, geo.top_info, geo.top_order
    kinds, params, meshes = geo.shape_kind, geo.shape_param, geo.shape_index
    transforms, roots = geo.shape_object_from_world, geo.mesh_root
    boxes, links, corners = geo.node_boxes, geo.node_links, geo.tri_corners
    inverse_d = inverse(d)
    best_shape, best_t, best_part, best_b1, best_b2 = -1, t_max, -1, 0.0, 0.0
    node = -1
    if info.shape[0] > 0 and box_entry(bounds, 0, o, inverse_d, 0.0, t_max) != NO_HIT:
        node = 0
    top = 0
    while node >= 0:
        count = info[node, 1]
        if count > 0:
            first = info[node, 0]
            for k in range(first, first + count):
                shape = order[k]
                kind = kinds[shape]
                if kind == SHAPE_CSG:
                    row, t, part, b1, b2 = csg_closest(geo, meshes[shape], o, d, best_t, scratch)
                    if t < best_t:
                        best_shape, best_t, best_part, best_b1, best_b2 = row, t, part, b1, b2
                    continue
                o_obj = affine_point(transforms, shape, o)
                d_obj = affine_vector(transforms, shape, d)
                if kind == SHAPE_MESH:
                    t, part, b1, b2 = mesh_closest(
                        boxes, links, corners, roots[meshes[shape]], o_obj, d_obj, best_t,
                        mesh_stack, mesh_stack_t,
                    )  # fmt: skip
                else:
                    major, minor = params[shape, 0], params[shape, 1]
                    t, part = intersect_analytic(kind, major, minor, o_obj, d_obj, 0.0, best_t)
                    b1 = b2 = 0.0
                if t < best_t:
                    best_shape, best_t, best_part, best_b1, best_b2 = shape, t, part, b1, b2
            node = -1
        else:
            node, top = descend(bounds, info[node, 0], o, inverse_d, best_t, stack, stack_t, top)
        if node < 0:
            node, top = pop_nearer(stack, stack_t, top, best_t)
    if best_shape < 0:
        return -1, NO_HIT, -1, 0.0, 0.0
    return best_shape, best_t, best_part, best_b1, best_b2


@inlined_kernel
def descend_in_order(bounds, child, o, inverse_d, t_max, stack, top):
    """`descend` for queries that want every hit, not the nearest: the left child first,
    whatever the distances, so leaves come in leaf order. Returns (next node or -1, top)."""
    left = box_entry(bounds, child, o, inverse_d, 0.0, t_max) != NO_HIT
    right = box_entry(bounds, child + 1, o, inverse_d, 0.0, t_max) != NO_HIT
    if left and right:
        stack[top] = child + 1
        return child, top + 1
    if left:
        return child, top
    return (child + 1 if right else -1), top


@inlined_kernel
def shape_transmittance(geo, shape, o, d, t_max, stacks):
    """The fraction of light that passes shape `shape` along o + t d, 0 < t < t_max: 1 when
    the segment misses it, 0 when it crosses an opaque surface of it, else the product of
    the crossed surfaces' transparencies (the rule of `transmittance`). A surface whose
    share varies over it (SHADOW_VARIES) counts 1 here, its crossings listed for the
    integrator to answer (`core.kernels.shadow_log`)."""
    tau = geo.shape_transparency[shape]
    if tau == 1.0:
        return 1.0
    kind = geo.shape_kind[shape]
    if kind == SHAPE_CSG:
        return csg_transmittance(geo, geo.shape_index[shape], o, d, t_max, stacks)
    if tau == SHADOW_VARIES:
        if kind == SHAPE_MESH:
            return mesh_varying(geo, shape, o, d, t_max, stacks)
        return analytic_varying(geo, shape, o, d, t_max, stacks)
    o_obj = affine_point(geo.shape_object_from_world, shape, o)
    d_obj = affine_vector(geo.shape_object_from_world, shape, d)
    root = geo.mesh_root[geo.shape_index[shape]] if kind == SHAPE_MESH else -1
    if kind == SHAPE_MESH and tau > 0.0:
        # light passes: each crossing counts, once where triangles meet (-1: too many)
        crossings = mesh_surface_crossings(
            geo.node_boxes, geo.node_links, geo.tri_corners, root, o_obj, d_obj, t_max,
            stacks.csg.cross_f, stacks.csg.cross_i, stacks.mesh,
        )  # fmt: skip
        if crossings < 0:
            return 0.0
    elif kind == SHAPE_MESH:
        crossings = mesh_crossings(
            geo.node_boxes, geo.node_links, geo.tri_corners, root,
            o_obj, d_obj, 0.0, t_max, True, None, None, stacks.mesh,
        )  # fmt: skip
    else:
        major, minor = geo.shape_param[shape, 0], geo.shape_param[shape, 1]
        crossings = count_crossings(kind, major, minor, o_obj, d_obj, 0.0, t_max)
    if crossings == 0:
        return 1.0
    if tau == 0.0:
        return 0.0
    return tau**crossings


@inlined_kernel
def tint_by(geo, shape, factor, tint):
    """Multiply `tint` (3,) by the colour of `factor` (share^n, n crossings of shape's
    surface): colour^n / share^n = factor^(p - 1) per channel (Geometry.shape_shadow_power)."""
    power = geo.shape_shadow_power
    if power[shape, 0] != 1.0 or power[shape, 1] != 1.0 or power[shape, 2] != 1.0:
        for c in range(3):
            tint[c] *= factor ** (power[shape, c] - 1.0)


@optimised_alone
@inlined_kernel
def transmittance(geo, o, d, t_max, stacks, listed):
    """The fraction of light that passes along o + t d, 0 < t < t_max (shadow rays).

    The rule for transparent objects: each crossing of a surface multiplies the light by
    its share (Geometry.shape_transparency, `core.compile.materials.shadow_shares`): what
    passes it straight, plus, under the "attenuated" glass-shadow rule, its transparency tau,
    without bending or Fresnel loss (a shadow ray cannot follow refraction to the light).
    Surfaces of share 0 block it outright, and the search stops at the first of them, as an
    any-hit query.

    Which shapes are tried: with listed < 0 (TRAVERSE_ALL), those whose boxes the top-level
    BVH finds along the ray; with listed >= 0, only the first `listed` shapes of
    stacks.candidates (an area light's pyramid, `core.kernels.light_pyramid`), and first of
    them the one that stopped this thread's previous shadow ray, if listed (an occluder
    cache: a point in full shadow costs one shape test per ray). Either way the factors are
    multiplied in leaf order, so the two give the same bits.

    The light's colour goes into stacks.shadow_tint, a factor of the returned fraction per
    channel: 1 unless coloured transparent surfaces are crossed (`tint_by`); left as it is
    (1 from the start) in a scene where no shadow can be coloured.

    One loop serves both sources, so that the shape tests are compiled once."""
    bounds, info, order = geo.top_bounds, geo.top_info, geo.top_order
    stack, candidates, occluder = stacks.top, stacks.candidates, stacks.occluder
    inverse_d = inverse(d)
    light = 1.0
    tint = stacks.shadow_tint
    coloured = geo.shape_shadow_power.shape[0] != 0  # else no row is: no colour is kept
    if coloured:
        tint[0] = tint[1] = tint[2] = 1.0
    # Traversal state: the next node to open, and the leaf's shapes order[k:end] being tried
    node = -1
    if (
        listed < 0
        and info.shape[0] > 0
        and box_entry(bounds, 0, o, inverse_d, 0.0, t_max) != NO_HIT
    ):
        node = 0
    top = k = end = 0
    # List state: position c in candidates; -1 tries the cached occluder first
    hinted = occluder[OCCLUDER_POSITION] if listed > 0 else -1
    hinted_factor = 1.0
    c = -1 if hinted >= 0 else 0
    while True:
        probe = False
        position = -1
        if listed >= 0:
            if c >= listed:
                break
            probe = c < 0
            position = hinted if probe else c
            c += 1
            if position == hinted and not probe:
                light *= hinted_factor
                if coloured and hinted_factor != 1.0:
                    tint_by(geo, candidates[hinted], hinted_factor, tint)
                continue
            shape = candidates[position]
            if box_entry(geo.shape_bounds, shape, o, inverse_d, 0.0, t_max) == NO_HIT:
                continue
        elif k < end:
            shape = order[k]
            k += 1
        else:
            leaf = -1
            while leaf < 0 and (node >= 0 or top > 0):
                if node < 0:
                    top -= 1
                    node = stack[top]
                if info[node, 1] > 0:
                    leaf, node = node, -1
                else:
                    node, top = descend_in_order(
                        bounds, info[node, 0], o, inverse_d, t_max, stack, top
                    )
            if leaf < 0:
                break
            k, end = info[leaf, 0], info[leaf, 0] + info[leaf, 1]
            continue
        factor = shape_transmittance(geo, shape, o, d, t_max, stacks)
        if factor == 0.0:
            if listed >= 0:
                occluder[OCCLUDER_SHAPE], occluder[OCCLUDER_POSITION] = shape, position
            return 0.0
        if probe:
            hinted_factor = factor
        else:
            light *= factor
            if coloured and factor != 1.0:
                tint_by(geo, shape, factor, tint)
    return light


@kernel
def spawn_point(p, n, ray_origin):
    """A start point for rays leaving the surface at p on the side n points to."""
    magnitude = max(max_abs(p), max_abs(ray_origin))
    return add(p, scale(n, SPAWN_OFFSET_RELATIVE * magnitude + SPAWN_OFFSET_ABSOLUTE))
