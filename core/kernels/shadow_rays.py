"""A light's shadow rays at one shading point: every sample's ray, or (adaptive soft
shadows) nine probe rays first and the samples' own rays only where the probes disagree.

Adaptive soft shadows (OPTION_SHADOW_ADAPTIVE), as POV-Ray's `adaptive` area lights and
Whitted's own 1980 paper spend rays: a point fully lit by a light, or wholly in its shadow,
sees the same through every part of it. The probes are the light's outline at eight points
and its centre (`probe_square`); when all nine rays are cast and return exactly the same
transmittance, with no surface on them whose transparency varies, every sample of the light
is given that transmittance and no more rays are cast; otherwise each sample's ray is cast
as without probes. A sample's shading (its direction, distance, weight and cosines) is
computed as always: only the rays are skipped. So a point is lit exactly as by the full set
wherever the probes' verdict holds for every sample, and the pixels differ only where an
occluder falls between the probes (one narrower than the light's half-width, seen from a
point the probes all pass, or a shadow's edge cutting off the sliver of a disk between two
rim probes) -- the method's known blind spot, measured in tests/core/test_adaptive_shadows.

The decision takes a slot of the shading point's log (core.kernels.shadow_log), so that a
replay (the varying surfaces answered) decides as the first pass did and casts, or reads
back, the same rays in the same order.
"""

from ..jit.decorators import inlined_kernel, ir_inlined_kernel, kernel, never_inlined
from .options import EMITTER_SPHERE, EMITTER_SUN_CONE
from .shadow_log import PROBES, STATE_CROSSINGS, STATE_RAY, STATE_REPLAY
from .trace import transmittance
from .vec import dot, row
from .workspace import SHADOW_RAYS, SHADOW_RAYS_UNOBSTRUCTED

# Below this many samples the probes cost about what they save: every sample's ray is cast
MIN_ADAPTIVE_SAMPLES = 2 * PROBES


@inlined_kernel
def probe_square(kind, k):
    """The unit-square point (a, b) of probe k of a light of emitter `kind` (the report's
    rectangles pass -1): eight points around the square's edge (its corners and the
    midpoints of its sides) and its centre, where the light maps the square onto itself or
    a disk (the edge lands on the disk's rim); for a cone of directions (a: 1 - cos across
    the cone, b: the turn about its axis) eight points of the rim an eighth of a turn apart
    and the axis. Eight, not four: a straight shadow edge cutting a disk between four rim
    points hides up to 9% of it from them, between eight 1.2%."""
    if k == PROBES - 1:
        return (0.0, 0.0) if _is_cone(kind) else (0.5, 0.5)
    if _is_cone(kind):
        return 1.0, k / (PROBES - 1.0)
    side, along = k // 2, 0.5 * (k % 2)  # around the square from (0, 0), a half-side a step
    if side == 0:
        return along, 0.0
    if side == 1:
        return 1.0, along
    if side == 2:
        return 1.0 - along, 1.0
    return 0.0, 1.0 - along


@inlined_kernel
def _is_cone(kind):
    return kind == EMITTER_SPHERE or kind == EMITTER_SUN_CONE  # noqa: SIM109 (numba's ints)


@never_inlined
@kernel
def shadow_visibility(geo, stacks, listed, origin, n, first, end):
    """Transmittance along rows first..end-1 of stacks.light_targets (unit direction,
    distance) from `origin` into stacks.visibility: the shadow rays of one light at one
    point. Rays towards lights behind the surface (N.L <= 0) or at distance 0 are not cast
    (their visibility is left as it was); `listed` as in `trace.transmittance` (0: nothing
    can block them).

    A call of its own, apart from the shading that uses its results: with a shadow ray's
    call inside the loop over samples, the loop kept its values in memory across the call,
    and shading an unobstructed sample cost 2.3 times as much (210 ns against 91)."""
    targets, visibility, tint = stacks.light_targets, stacks.visibility, stacks.visibility_tint
    state, log, log_tint = stacks.shadow_state, stacks.shadow_log, stacks.shadow_log_tint
    replay = state[STATE_REPLAY] != 0
    # without coloured shadows in the scene every tint stays 1, as the workspace began
    coloured = geo.shape_shadow_power.shape[0] != 0
    for j in range(first, end):
        distance = targets[j, 3]
        light_dir = row(targets, j)
        if distance == 0.0 or dot(n, light_dir) <= 0.0:
            continue
        g = state[STATE_RAY]  # this ray's number in the point's log (core.kernels.shadow_log)
        if replay and g < log.shape[0]:
            visibility[j] = log[g]  # its varying crossings answered since it was cast
            if coloured:
                tint[j, 0], tint[j, 1] = log_tint[g, 0], log_tint[g, 1]
                tint[j, 2] = log_tint[g, 2]
        elif listed == 0:
            if not replay:
                stacks.ray_counts[SHADOW_RAYS_UNOBSTRUCTED] += 1
            visibility[j] = 1.0
            if coloured:
                tint[j, 0] = tint[j, 1] = tint[j, 2] = 1.0
        else:
            listed_before = state[STATE_CROSSINGS]
            visible = transmittance(geo, origin, light_dir, distance, stacks, listed)
            if visible == 0.0:
                state[STATE_CROSSINGS] = listed_before  # blocked: its crossings do not matter
            visibility[j] = visible
            if coloured:
                colour = stacks.shadow_tint
                tint[j, 0], tint[j, 1], tint[j, 2] = colour[0], colour[1], colour[2]
        if not replay:
            stacks.ray_counts[SHADOW_RAYS] += 1
        if g < log.shape[0]:
            log[g] = visibility[j]
            if coloured:
                log_tint[g, 0], log_tint[g, 1] = tint[j, 0], tint[j, 1]
                log_tint[g, 2] = tint[j, 2]
        state[STATE_RAY] = g + 1


@ir_inlined_kernel
def light_visibility(geo, stacks, listed, origin, n, count, adaptive):
    """The visibility of a light's `count` samples (rows 0..count-1 of light_targets) into
    stacks.visibility. With `adaptive`, rows count..count+PROBES-1 hold the probes' targets
    (aimed by the caller as the samples are) and decide first (the module's rule).

    Inlined by numba, not a function of its own: numba optimises the code a function calls
    again with each function compiled, and a function between the lights and
    `shadow_visibility` (even one LLVM inlines) added a copy of the shadow-ray code to the
    cold compile (+130 s, then +70 s)."""
    visibility, state, log = stacks.visibility, stacks.shadow_state, stacks.shadow_log
    probing = adaptive and count >= MIN_ADAPTIVE_SAMPLES and listed != 0
    first, end = (count, count + PROBES) if probing else (0, count)
    g = state[STATE_RAY]  # with probes, the decision's own slot in the log
    if probing:
        state[STATE_RAY] = g + 1
        for k in range(PROBES):
            visibility[count + k] = -1.0  # left so by a probe that is not cast
    crossings_before = state[STATE_CROSSINGS]
    # One call site of shadow_visibility, for the probes and then (unless they agree) the
    # samples: a second one cost the cold compile 50 s
    while True:
        shadow_visibility(geo, stacks, listed, origin, n, first, end)
        if first == 0:
            return
        seen = visibility[count]
        tint = stacks.visibility_tint
        agree = seen >= 0.0 and state[STATE_CROSSINGS] == crossings_before
        for k in range(1, PROBES):
            agree = agree and visibility[count + k] == seen
            for c in range(3):  # (all 1 without coloured shadows in the scene)
                agree = agree and tint[count + k, c] == tint[count, c]
        if g >= log.shape[0]:
            agree = False  # no slot to keep the decision in for a replay: every ray, always
        elif state[STATE_REPLAY] != 0:
            agree = log[g] != 0.0  # as the first pass decided
        else:
            log[g] = 1.0 if agree else 0.0
        if agree:
            for j in range(count):
                visibility[j] = seen
                tint[j, 0], tint[j, 1], tint[j, 2] = tint[count, 0], tint[count, 1], tint[count, 2]
            return
        first, end = 0, count
