"""The answers to a shading point's listed crossings of surfaces whose share varies
(`core.kernels.shadow_log`): the crossed surface's material program run at each, by the
integrator (the photon pass, core.kernels.photons, compiles its own call)."""

from ..jit.decorators import inlined_kernel, kernel
from ..vocabulary import GLASS_SHADOWS_ATTENUATED
from .attributes import READS_ATTRIBUTES, READS_FRAME, put_attributes
from .light_pyramid import TRAVERSE_ALL
from .options import OPTION_GLASS_SHADOWS
from .shader_program import ray_at, run_program
from .shadow_log import STATE_CROSSINGS, STATE_RAY, STATE_REPLAY, begin_point
from .surface import hit_frame, normal_rows, surface_at
from .surface_terms import terms_from_lobes
from .trace import transmittance


@inlined_kernel
def crossing_share(geo, surf, mats, ws, shape, part, b1, b2, o, d, t, refraction_passes):
    """What shape row `shape`'s surface lets a shadow ray o + t d through where it crosses
    it (part, b1, b2 as a nearest hit gives them): the rule of a constant material's
    share (`core.compile.materials.shadow_shares`), the mean of what passes it straight
    plus, if `refraction_passes`, its transparency, at most 1, with the terms its program
    gives there; and its colour, per channel over that share."""
    material = surf.shape_material[shape]
    p, n_geometric, n_shading, u, v = surface_at(geo, surf, shape, part, b1, b2, o, d, t, True)
    reads = mats.shader_frame[material]
    hit, across = hit_frame(geo, surf, shape, part, p, n_shading, u, v, (reads & READS_FRAME) != 0)
    if reads & READS_ATTRIBUTES:
        put_attributes(geo, surf, shape, part, p, ws.shader_stack)
    rows = normal_rows(geo.shape_object_from_world, shape)
    # Light Path: a shadow ray (its depth is not known here: read as 0)
    ray = ray_at(0.0, 1.0, 0, p, d, n_geometric)
    run_program(mats, material, ws.shader_stack, ws.lobes, hit, across, rows, ray)
    here = terms_from_lobes(ws.lobes)
    clear = here.transparent
    straight = (clear[0] + clear[1] + clear[2]) / 3.0
    refracted = here.transparency if refraction_passes else 0.0
    share = min(1.0, max(0.0, refracted + straight))
    tint = (1.0, 1.0, 1.0)  # its colour per channel over the share (as trace.tint_by's)
    if share > 0.0 and (clear[0] != clear[1] or clear[1] != clear[2]):
        tint = (
            min(1.0, max(0.0, refracted + clear[0])) / share,
            min(1.0, max(0.0, refracted + clear[1])) / share,
            min(1.0, max(0.0, refracted + clear[2])) / share,
        )
    return share, tint


@inlined_kernel
def answer_crossings(geo, surf, mats, ws, refraction_passes):
    """Multiply each listed crossing's share into its shadow ray's logged visibility, and
    set the log to be replayed. False when nothing was listed: the point is lit already.
    `refraction_passes`: the glass-shadow rule (OPTION_GLASS_SHADOWS is "attenuated")."""
    stacks = ws.stacks
    state, log, log_tint = stacks.shadow_state, stacks.shadow_log, stacks.shadow_log_tint
    f, i = stacks.varying_f, stacks.varying_i
    count = state[STATE_CROSSINGS]
    if count == 0:
        return False
    for c in range(count):
        g = i[c, 2]
        if log[g] == 0.0:
            continue  # an earlier crossing of the same ray blocked it
        o, d = (f[c, 3], f[c, 4], f[c, 5]), (f[c, 6], f[c, 7], f[c, 8])
        shape, part, b1, b2, t = i[c, 0], i[c, 1], f[c, 1], f[c, 2], f[c, 0]
        share, tint = crossing_share(geo, surf, mats, ws, shape, part, b1, b2, o, d, t,
                                     refraction_passes)  # fmt: skip
        log[g] *= share
        for a in range(3):
            log_tint[g, a] *= tint[a]
    state[STATE_RAY] = 0
    state[STATE_CROSSINGS] = 0
    state[STATE_REPLAY] = 1
    return True


@kernel
def light_along(ps, ws, o, d, t_max):
    """What one shadow ray o + t d, 0 < t < t_max, lets through by the full rule: its
    transmittance with the crossings of varying surfaces answered (for tests and tools;
    `core.kernels.batch.shadow_rays` answers the constant shares alone)."""
    geo, surf, mats = ps.geometry, ps.surfaces, ps.materials
    refraction_passes = ps.frame.options[OPTION_GLASS_SHADOWS] == GLASS_SHADOWS_ATTENUATED
    stacks = ws.stacks
    begin_point(stacks.shadow_state)
    light = transmittance(geo, o, d, t_max, stacks, TRAVERSE_ALL)
    stacks.shadow_log[0] = light
    if light > 0.0:
        answer_crossings(geo, surf, mats, ws, refraction_passes)
    return stacks.shadow_log[0]
