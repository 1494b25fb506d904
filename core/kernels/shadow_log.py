"""Shadow rays through surfaces whose transparency varies over them: an image's alpha on a
leaf card, a Transparent BSDF mixed in by a mask, glass with a textured colour.

A material whose terms are constant lets a shadow ray through by one number per crossing
(Geometry.shape_transparency). A node material that may let light through and whose terms
vary from point to point is marked SHADOW_VARIES there instead: how much it lets through
is its program's answer at the crossing, the same program and rule as at a camera ray's
hit. Running that program inside the shadow path put its code under every function that
casts shadow rays and tripled the kernels' cold compile (115 s to 296 s), so the shadow
path only writes down where each such crossing is, and the integrator answers them all
with the one program call it has:

1. While a shading point is lit, every shadow ray cast gets the next number g, and its
   visibility without the varying surfaces (they count as 1 for now) is kept in
   Stacks.shadow_log[g]; each crossing of a varying surface is listed with g.
2. If any were listed, the integrator runs the material's program at each
   (`core.kernels.shadow_crossing`), multiplies its share into shadow_log[g], and lights
   the point again in replay: the same lights, the same samples, each shadow ray's
   visibility read back from the log instead of traced. The sums are linear in the
   visibilities, so this is the picture the full rule gives; a point whose shadow rays
   meet no varying surface is lit once, exactly as before.

A ray numbered past the log, or whose crossings do not fit the list, is taken as blocked
and counted (RenderStats' warning), never lit wrongly without a word.
"""

from ..jit.decorators import inlined_kernel
from .mesh_trace import mesh_surface_crossings
from .shapes import NO_HIT, intersect_analytic
from .vec import affine_point, affine_vector

# Geometry.shape_transparency's mark for a surface whose share is its program's at each crossing
SHADOW_VARIES = -1.0

# Shadow rays one shading point may cast with their visibility kept (lights x samples), and
# crossings of varying surfaces listed at one point (16 samples through 64 leaves)
SHADOW_LOG_SIZE = 4096
# Adaptive soft shadows' probe rays per light and shading point, beside its samples in
# Stacks.light_targets: eight points of the light's outline and its centre
# (core.kernels.shadow_rays)
PROBES = 9
VARYING_CAPACITY = 1024

# Slots of Stacks.shadow_state: the number of the shadow ray being cast (the next, between
# rays); crossings listed; 1 while replaying; shadow rays taken as blocked for lack of room
STATE_RAY, STATE_CROSSINGS, STATE_REPLAY, STATE_OVERFLOWED = 0, 1, 2, 3
SHADOW_STATE_SLOTS = 4


@inlined_kernel
def begin_point(state):
    """Start the log of a shading point's shadow rays (before its lights are summed)."""
    state[STATE_RAY] = 0
    state[STATE_CROSSINGS] = 0
    state[STATE_REPLAY] = 0


@inlined_kernel
def record_crossing(stacks, shape, part, t, b1, b2, o, d):
    """List a crossing of varying shape row `shape` by the shadow ray o + t d being cast
    (part, b1, b2 as a nearest hit gives them). False when there is no room: the ray is
    then taken as blocked."""
    state = stacks.shadow_state
    g, n = state[STATE_RAY], state[STATE_CROSSINGS]
    if g >= stacks.shadow_log.shape[0] or n >= stacks.varying_i.shape[0]:
        if state[STATE_REPLAY] == 0:  # a ray recast in replay was counted when first cast
            state[STATE_OVERFLOWED] += 1
        return False
    f, i = stacks.varying_f, stacks.varying_i
    f[n, 0], f[n, 1], f[n, 2] = t, b1, b2
    f[n, 3], f[n, 4], f[n, 5] = o
    f[n, 6], f[n, 7], f[n, 8] = d
    i[n, 0], i[n, 1], i[n, 2] = shape, part, g
    state[STATE_CROSSINGS] = n + 1
    return True


@inlined_kernel
def mesh_varying(geo, shape, o, d, t_max, stacks):
    """List the crossings of mesh row `shape` (marked SHADOW_VARIES) along o + t d,
    0 < t < t_max, merged where triangles meet (`mesh_trace.mesh_surface_crossings`, as a
    constant share counts them). 1.0, or 0.0 (blocked) when they do not fit."""
    o_obj = affine_point(geo.shape_object_from_world, shape, o)
    d_obj = affine_vector(geo.shape_object_from_world, shape, d)
    cross_f, cross_i = stacks.csg.cross_f, stacks.csg.cross_i
    events = mesh_surface_crossings(
        geo.node_boxes, geo.node_links, geo.tri_corners, geo.mesh_root[geo.shape_index[shape]],
        o_obj, d_obj, t_max, cross_f, cross_i, stacks.mesh,
    )  # fmt: skip
    if events < 0:
        return 0.0
    for c in range(events):
        t, b1, b2 = cross_f[c, 0], cross_f[c, 1], cross_f[c, 2]
        if not record_crossing(stacks, shape, cross_i[c, 0], t, b1, b2, o, d):
            return 0.0
    return 1.0


@inlined_kernel
def analytic_varying(geo, shape, o, d, t_max, stacks):
    """List the crossings of analytic shape row `shape` (marked SHADOW_VARIES) along
    o + t d, 0 < t < t_max, found in order. 1.0, or 0.0 (blocked) when they do not fit."""
    o_obj = affine_point(geo.shape_object_from_world, shape, o)
    d_obj = affine_vector(geo.shape_object_from_world, shape, d)
    kind = geo.shape_kind[shape]
    major, minor = geo.shape_param[shape, 0], geo.shape_param[shape, 1]
    t_from = 0.0
    while True:
        # the roots are computed alike each time, so t_from > the last one skips it exactly
        t, part = intersect_analytic(kind, major, minor, o_obj, d_obj, t_from, t_max)
        if t == NO_HIT:
            return 1.0
        if not record_crossing(stacks, shape, part, t, 0.0, 0.0, o, d):
            return 0.0
        t_from = t
