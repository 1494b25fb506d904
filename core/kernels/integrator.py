"""Whitted's recursion without recursion: the tree of reflected and refracted rays, walked
depth-first with an explicit stack from the `Workspace`.

At each hit of a ray carrying weight w (what its colour counts for in the pixel), with the
material's row of the table (core.model.Material names the fields):

    colour += w (1 - tau) local + w emission      local = the report's Phong lighting, its
                                                    kd dimmed by (1 - c Fc) when the coat hides
    reflected ray, weight w ((1 - tau) (rho M + c Fc) + tau F Gr)
    refracted ray, weight w tau (1 - k F) Gt          k = refraction_fresnel (1: glass)
    a ray straight on, weight w T

with rho the material's reflectivity, M its mirror tint c0 + (c90 - c0)(1 - cos)^5
(Schlick's), c and Fc the coat's weight and exact Fresnel reflectance for its IOR, tau its
transparency, F the exact dielectric Fresnel reflectance for the indices on the two sides
(outer and inner IOR, swapped when the ray leaves the object; past the critical angle F = 1,
total internal reflection), Gr and Gt the glass tints, T what passes straight through. With
the report's materials (tints 1, no coat, nothing straight through) this is the report's
formula to the bit. Inside an object whose material absorbs (Volume Absorption), each ray
keeps exp(-sigma t) of its weight over the length t it travels there (core.kernels.absorption).
Rays stop after `max_depth` bounces, or once their weight can no longer
show (MIN_WEIGHT); rays going straight on do not bounce, and stop after MAX_CROSSINGS.

A shape that the ray's kind does not see (core.model.Shape.seen_by_camera, seen_in_mirrors,
seen_through_glass) is passed as if absent: the ray goes on from its far side.
"""

import math

from ..jit.decorators import inlined_kernel, kernel
from ..vocabulary import GLASS_SHADOWS_ATTENUATED
from .absorption import NO_MEDIUM, absorbed, medium_beyond
from .bent_normal import terminator_model
from .clear_coat import NO_GLINT, coat_glint, coat_normal, coat_reflectance, under_coat
from .emitters_seen import emitters_seen
from .environment import environment_seen
from .features import (
    WITH_CLEAR_COAT,
    WITH_EMITTERS_SEEN,
    WITH_GLOSSY,
    WITH_PASSES,
    WITH_TRANSLUCENT,
)
from .fresnel import fresnel_dielectric
from .glossy import visible_normal
from .layout import VISIBLE_CAMERA, VISIBLE_GLOSSY, VISIBLE_TRANSMISSION
from .light_at_point import light_at_point
from .light_samples import stratified_cell
from .material_at_hit import material_at_hit
from .microfacet import (
    dielectric_fresnel_mean,
    is_white,
    rough_coat_albedo,
    schlick_dip,
    tinted_fresnel,
)
from .options import (
    OPTION_BUMP_TERMINATOR,
    OPTION_GLASS_SHADOWS,
    OPTION_GLOSSY_SAMPLES,
    OPTION_MAX_DEPTH,
    OPTION_PASSES,
    OPTION_TRANSPARENT,
    PASSES_LIGHT_SPLIT,
    PASSES_UV,
)
from .pass_record import (
    REC_DIFFUSE,
    REC_EMISSION,
    REC_ENVIRONMENT,
    REC_REFLECTION,
    REC_REFRACTION,
    add_to,
    clear,
    record_hit,
    record_lighting,
)
from .rng import PURPOSE_CLEAR_COAT, PURPOSE_GLOSSY, uniform2
from .shader_program import SHARP_ROUGHNESS, path_ray_at
from .shading import Phong, ShadingPoint
from .surface import surface_at
from .trace import closest_hit, spawn_point
from .translucent import translucent_light
from .vec import add, cross, dot, mul, normalize, row, scale, sub
from .workspace import MAX_CROSSINGS, RAYS_TRACED

MIN_WEIGHT = 1e-6
# How a ray left its last surface (RayStack.refracted): the lights in Blender's units it
# sees depend on it (a rough mirror's glint holds their light already)
RAY_REFLECTED, RAY_REFRACTED, RAY_ROUGH_REFLECTED = 0, 1, 2


@kernel
def refract(d, n, eta, cos_i, cos_t):
    """Snell's law: unit d through the surface with unit normal n facing the incoming ray,
    eta = n1 / n2, cos_i = -d.n and cos_t from `fresnel_dielectric`."""
    return normalize(add(scale(d, eta), scale(n, eta * cos_i - cos_t)))


@kernel
def _push(rays, top, o, d, w, depth, branch, refracted, medium, crossed, refractions):
    """Put a ray on the stack; one too faint to show, or with no room left, is dropped
    (`core.kernels.workspace` sizes the stack for max_depth and MAX_CROSSINGS). `medium`:
    the material row of the medium it travels in (core.kernels.absorption); `crossed` and
    `refractions`: the transparent surfaces it passed and the refractions among its
    bounces, for Light Path."""
    if max(w[0], w[1], w[2]) < MIN_WEIGHT or top >= rays.depth.shape[0]:
        return top
    for a in range(3):
        rays.origin[top, a] = o[a]
        rays.direction[top, a] = d[a]
        rays.weight[top, a] = w[a]
    rays.depth[top] = depth
    rays.branch[top] = branch
    rays.refracted[top] = refracted
    rays.crossed[top] = crossed
    rays.medium[top] = medium
    rays.refractions[top] = refractions
    return top + 1


@kernel
def _sees(visibility, depth, came_through):
    """Whether a ray of this kind stops at a shape of these VISIBLE_* bits."""
    if depth == 0:
        return (visibility & VISIBLE_CAMERA) != 0
    if came_through:
        return (visibility & VISIBLE_TRANSMISSION) != 0
    return (visibility & VISIBLE_GLOSSY) != 0


@kernel
def channel_mean(w):
    return (w[0] + w[1] + w[2]) / 3.0


@kernel
def mirror_tint(here, cos_i):
    """The mirror's tint at this incidence: Schlick's c0 + (c90 - c0)(1 - cos)^5, less F82's
    dip where a metal has an F82 tint (core.kernels.microfacet.schlick_dip)."""
    return schlick_dip(here.mirror_normal, here.mirror_edge, here.mirror_dip, cos_i)


@kernel
def _leave_surface(rays, top, here, sample, samples, spread, key, event, o, d, w, p, n_shading,
                   n_geometric, outside, cos_i, tau, rho, coat_reflects, coat_colour, entering,
                   depth, branch, medium, beyond, refractions):  # fmt: skip
    """Push the reflected and refracted rays of glossy sample `sample` of `samples` leaving a
    surface (`spread`: by a microfacet normal drawn from its lobe, core.kernels.glossy; else
    by the shading normal, one sample); the reflected ray stays in `medium`, the refracted
    one travels in `beyond` (core.kernels.absorption). A call of its own: in the
    integrator's body its loop cost the render kernel's cold compile 11 s more (183 s
    against 172)."""
    share = 1.0 / samples
    m, cos_m = n_shading, cos_i
    if WITH_GLOSSY and spread:
        a, b = uniform2(key, PURPOSE_GLOSSY, event, sample)
        x0, y0, cell_w, cell_h = stratified_cell(sample, samples)
        alpha_m = max(here.roughness * here.roughness, 1e-6)
        m = visible_normal(scale(d, -1.0), n_shading, alpha_m, x0 + a * cell_w,
                           y0 + b * cell_h)  # fmt: skip
        cos_m = min(1.0, max(0.0, -dot(d, m)))
    reflect = (0.0, 0.0, 0.0)
    if rho > 0.0:
        reflect = scale(mirror_tint(here, cos_m), (1.0 - tau) * rho)
    if coat_reflects > 0.0:
        reflect = add(reflect, scale(coat_colour, (1.0 - tau) * coat_reflects))
    if tau > 0.0:
        outer, inner = here.outer_ior, here.inner_ior
        n1, n2 = (outer, inner) if entering else (inner, outer)
        f, cos_t = fresnel_dielectric(cos_m, n1, n2)
        reflect = add(reflect, scale(here.glass_reflect, tau * f))
        # the share Fresnel takes from the refracted ray: all of F for glass
        f_lost = f * here.refraction_fresnel
        if f < 1.0:
            refracted = refract(d, m, n1 / n2, cos_m, cos_t)
            if not spread or dot(refracted, n_geometric) < 0.0:
                inside = spawn_point(p, scale(n_geometric, -1.0), o)
                through = REC_REFRACTION if depth == 0 else branch
                weight = mul(w, scale(here.glass_transmit, tau * (1.0 - f_lost) * share))
                top = _push(rays, top, inside, refracted, weight, depth + 1, through,
                            RAY_REFRACTED, beyond, 0, refractions + 1)  # fmt: skip
    if reflect[0] > 0.0 or reflect[1] > 0.0 or reflect[2] > 0.0:
        reflected = sub(d, scale(m, 2.0 * dot(d, m)))
        if not spread or dot(reflected, n_geometric) > 0.0:
            mirrored = REC_REFLECTION if depth == 0 else branch
            weight = mul(w, scale(reflect, share))
            kind = RAY_ROUGH_REFLECTED if here.mirror_hides_lights else RAY_REFLECTED
            top = _push(rays, top, outside, reflected, weight, depth + 1, mirrored, kind,
                        medium, 0, refractions)  # fmt: skip
    return top


@kernel
def _glossy_samples(frame, here, depth, rho, coat_reflects, tau):
    """(whether the rays leaving the surface spread over its rough lobe, by sampled
    microfacet normals (core.kernels.glossy), and how many: the camera ray's hit takes the
    setting's samples times the share of the light its lobes send on, deeper hits one).
    Off without the `glossy` feature: by the shading normal, one ray each way.

    The share: a pixel's noise from n rays of a lobe that sends on w of the light is
    w sigma / sqrt(n), so rays go where the light goes (n proportional to w spends them
    best): a rough metal or glass takes them all, a plastic's specular layer (4-10% of the
    light) a few."""
    if not WITH_GLOSSY:
        return False, 1
    glossy = frame.options[OPTION_GLOSSY_SAMPLES]
    spread = glossy > 0 and here.roughness > 0.0 and (rho > 0.0 or coat_reflects > 0.0
                                                      or tau > 0.0)  # fmt: skip
    if not spread or depth > 0:
        return spread, 1
    mirror = rho * max(max(here.mirror_normal), max(here.mirror_edge))
    share = min(max(mirror, coat_reflects, tau), 1.0)
    return spread, max(1, int(math.ceil(glossy * share)))


@kernel
def _leave_clear_coat(rays, top, coat, n_coat, sample, samples, spread, key, event, d, w,
                      outside, n_geometric, depth, branch, medium, refractions):  # fmt: skip
    """Push the ray the clear coat reflects (core.kernels.clear_coat) for glossy sample
    `sample` of `samples`: about the coat's normal, or a microfacet normal drawn from its
    own lobe (`spread`), its weight the exact Fresnel there."""
    m = n_coat
    if WITH_GLOSSY and spread:
        a, b = uniform2(key, PURPOSE_CLEAR_COAT, event, sample)
        x0, y0, cell_w, cell_h = stratified_cell(sample, samples)
        alpha_m = max(coat.roughness * coat.roughness, 1e-6)
        m = visible_normal(scale(d, -1.0), n_coat, alpha_m, x0 + a * cell_w, y0 + b * cell_h)
    cos_m = min(1.0, max(0.0, -dot(d, m)))
    f, _ = fresnel_dielectric(cos_m, 1.0, coat.ior)
    reflected = sub(d, scale(m, 2.0 * dot(d, m)))
    if spread and dot(reflected, n_geometric) <= 0.0:
        return top
    weight = scale(w, coat.weight * f / samples)
    kind = RAY_ROUGH_REFLECTED if coat.roughness > SHARP_ROUGHNESS else RAY_REFLECTED
    mirrored = REC_REFLECTION if depth == 0 else branch
    return _push(rays, top, outside, reflected, weight, depth + 1, mirrored, kind, medium, 0,
                 refractions)  # fmt: skip


@kernel
def _clear_coat_samples(frame, coat, depth, reflects):
    """(`spread`, samples) for the clear coat's reflection, as _glossy_samples for the
    layers below: the coat's share of the light is what it `reflects`."""
    if not WITH_GLOSSY:
        return False, 1
    glossy = frame.options[OPTION_GLOSSY_SAMPLES]
    spread = glossy > 0 and coat.roughness > 0.0
    if not spread or depth > 0:
        return spread, 1
    return spread, max(1, int(math.ceil(glossy * min(reflects, 1.0))))


@inlined_kernel
def _seen_emitters(lights, o, d, t, came_through, depth, refracted_before):
    """Blender's lights seen in mirrors and through glass by a ray after its first bounce
    (the `emitters_seen` feature); none by a rough mirror's ray, whose glint holds them."""
    if not WITH_EMITTERS_SEEN or depth == 0 or refracted_before == RAY_ROUGH_REFLECTED:
        return (0.0, 0.0, 0.0)
    if lights.emitter_kind.shape[0] == 0:
        return (0.0, 0.0, 0.0)
    return emitters_seen(lights, o, d, t, came_through)


@inlined_kernel
def trace_ray(ps, o, d, key, ws):
    """(linear RGB colour seen along unit direction d from o, with every bounce; its alpha:
    0 for a camera ray that meets nothing under Film > Transparent, or meets a holdout,
    else 1). When passes are made, ws.record gets what they need of this camera ray
    (core.kernels.pass_record): each ray's colour goes to the term of its branch, the
    camera ray's own hit is split into ambient, diffuse and specular.

    The features (core.kernels.features) are calls of their own, each behind its constant
    where it is called, so that a variant without one never compiles its code: the
    material's terms (core.kernels.material_at_hit: node programs), the light at the point
    (core.kernels.light_at_point: Blender's lights, the World, varying shadows, caustics),
    lights seen in mirrors (`_seen_emitters`), the glossy spread (`_glossy_samples`) and the
    passes (core.kernels.pass_record)."""
    frame, geo, surf, mats, lights = ps
    stacks, rays, record = ws.stacks, ws.rays, ws.record
    max_depth = frame.options[OPTION_MAX_DEPTH]
    passes = frame.options[OPTION_PASSES] if WITH_PASSES else 0
    recording = passes != 0
    split = (passes & PASSES_LIGHT_SPLIT) != 0
    with_uv = (passes & PASSES_UV) != 0
    refraction_passes = frame.options[OPTION_GLASS_SHADOWS] == GLASS_SHADOWS_ATTENUATED
    if WITH_PASSES and recording:
        clear(record, 0.0)
    # Camera › Clip Start, along the view axis (up x right: a lens shift tilts the forward
    # row, not the image plane) from the eye's plane
    clip, clip_end, eye = frame.lens[5], frame.lens[6], row(frame.camera, 0)
    axis = normalize(cross(row(frame.camera, 3), row(frame.camera, 2)))
    colour = (0.0, 0.0, 0.0)
    alpha = 1.0
    top = _push(rays, 0, o, d, (1.0, 1.0, 1.0), 0, REC_ENVIRONMENT, 0, NO_MEDIUM, 0, 0)
    event = 0
    hit_recorded = False
    while top > 0:
        top -= 1
        o, d = row(rays.origin, top), row(rays.direction, top)
        w, depth, branch = row(rays.weight, top), rays.depth[top], rays.branch[top]
        # how it left its last surface (RAY_*)
        refracted_before = rays.refracted[top]
        came_through = refracted_before == RAY_REFRACTED
        crossed = rays.crossed[top]
        medium, refractions = rays.medium[top], rays.refractions[top]
        stacks.ray_counts[RAYS_TRACED] += 1
        reach = math.inf
        if depth == 0 and clip_end < math.inf:
            # Camera › Clip End, a plane across the view axis: a camera ray (or what passed
            # straight through) ends there, and sees the World beyond, as in Cycles
            toward = dot(d, axis)
            if toward > 0.0:
                reach = max((clip_end - dot(sub(o, eye), axis)) / toward, 0.0)
        shape, t, part, b1, b2 = closest_hit(geo, o, d, reach, stacks)
        # what the medium it crossed let through (core.kernels.absorption)
        w = absorbed(mats, medium, w, t if shape >= 0 else reach)
        glimpse = _seen_emitters(lights, o, d, t if shape >= 0 else reach, came_through,
                                 depth, refracted_before)  # fmt: skip
        if glimpse[0] > 0.0 or glimpse[1] > 0.0 or glimpse[2] > 0.0:
            seen = mul(w, glimpse)
            colour = add(colour, seen)
            if WITH_PASSES and recording:
                add_to(record, branch, seen)
        if shape < 0:
            if depth == 0 and frame.options[OPTION_TRANSPARENT] != 0:
                # a camera ray (or what passed straight through) meets nothing, not even
                # background: the pixel's alpha loses its share
                alpha -= channel_mean(w)
            else:
                seen = mul(w, environment_seen(frame, lights, d, depth, came_through))
                colour = add(colour, seen)
                if WITH_PASSES and recording:
                    add_to(record, branch, seen)
            continue
        # Camera › Clip Start: what a camera ray meets nearer than its plane is not seen
        # (passed as if absent); a segment starting before the plane counts its length from
        # the plane, as Cycles' rays start there
        length = t
        if depth == 0 and clip > 0.0:
            cos_axis = dot(d, axis)
            hit_depth = dot(sub(add(o, scale(d, t)), eye), axis)
            if dot(sub(o, eye), axis) < clip:
                length = (hit_depth - clip) / cos_axis
            if hit_depth < clip:
                length = -1.0  # hidden
        if length < 0.0 or not _sees(surf.shape_visibility[shape], depth, came_through):
            if crossed < MAX_CROSSINGS:
                p, n_geometric, _, _, _ = surface_at(geo, surf, shape, part, b1, b2, o, d, t, False)
                along = n_geometric if dot(d, n_geometric) > 0.0 else scale(n_geometric, -1.0)
                beyond = spawn_point(p, along, o)
                top = _push(rays, top, beyond, d, w, depth, branch, refracted_before, medium,
                            crossed + 1, refractions)  # fmt: skip
            continue
        if depth == 0 and surf.shape_holdout[shape] != 0:
            alpha -= channel_mean(w)  # a hole in the picture, as Cycles cuts: nothing behind shows
            continue
        material = surf.shape_material[shape]
        first = recording and depth == 0 and not hit_recorded
        textured = mats.texture[material] >= 0 or mats.shader_range[material, 0] >= 0
        p, n_geometric, n_shading, u, v = surface_at(
            geo, surf, shape, part, b1, b2, o, d, t, textured or (first and with_uv)
        )
        n_smooth = n_shading  # before the graph bends it (a coat keeps it)
        ray = path_ray_at(depth, p, d, n_geometric, came_through, length, crossed, refractions)
        here, n_shading, n_diffuse = material_at_hit(geo, surf, mats, ws, shape, material, part,
                                                     p, d, n_geometric, n_shading, u, v, ray,
                                                     first)  # fmt: skip
        tau = here.transparency
        rho = here.reflectivity
        # Face the side the ray came from
        entering = dot(d, n_geometric) < 0.0
        if not entering:
            n_geometric = scale(n_geometric, -1.0)
            n_shading = scale(n_shading, -1.0)
            n_diffuse = scale(n_diffuse, -1.0)
            n_smooth = scale(n_smooth, -1.0)
        outside = spawn_point(p, n_geometric, o)
        cos_i = min(1.0, max(0.0, -dot(d, n_shading)))
        beyond_medium = medium_beyond(mats, material, entering, medium)
        kd = here.kd
        # A clear coat over it all (core.kernels.clear_coat): what lies below, `w_below`
        coat = here.clear_coat
        coated = WITH_CLEAR_COAT and coat.weight > 0.0
        w_below, under, n_coat, coat_reflects_all = w, (1.0, 1.0, 1.0), n_smooth, 0.0
        if coated:
            n_coat = coat_normal(coat, d, n_geometric, n_smooth)
            coat_f = coat_reflectance(coat, min(1.0, max(0.0, -dot(d, n_coat))))
            under = under_coat(coat, min(1.0, max(0.0, -dot(d, n_coat))), coat_f)
            w_below = mul(w, under)
            kd = mul(kd, under)
            coat_reflects_all = coat.weight * coat_f
        coat_reflects = 0.0
        coat_colour = (1.0, 1.0, 1.0)  # its Specular Tint's, per channel
        if here.coat > 0.0:
            # a layer on the surface, air on its outer side from either side (Cycles' specular
            # layer does not flip its IOR on back faces)
            coat_f, _ = fresnel_dielectric(cos_i, 1.0, here.coat_ior)
            rough = here.gloss.coat > 0.0
            if not is_white(here.coat_tint):  # the Fresnel the tint reshapes: rough, the mean
                fresnel = coat_f
                if rough:
                    fresnel = dielectric_fresnel_mean(here.roughness, cos_i, here.coat_ior)
                coat_colour = tinted_fresnel(fresnel, here.coat_ior, here.coat_tint)
            if rough:  # a rough layer: its whole lobe's reflectance
                coat_f = rough_coat_albedo(here.gloss, here.roughness, cos_i)
            coat_reflects = here.coat * coat_f
            if here.coat_hides:  # the diffuse seen through the coat (Cycles: by its most)
                kd = scale(kd, 1.0 - coat_reflects * max(coat_colour))
        if depth == 0 and here.holdout > 0.0:
            alpha -= channel_mean(w) * here.holdout
        if WITH_PASSES and first:
            hit_recorded = True
            record_hit(record, surf, mats, shape, material, p, n_shading, u, v, 1.0 - tau, kd)
        emission = here.emission
        if emission[0] > 0.0 or emission[1] > 0.0 or emission[2] > 0.0:
            seen = mul(w_below, emission)  # under the coat, as in Cycles
            colour = add(colour, seen)
            if WITH_PASSES and first:
                add_to(record, REC_EMISSION, seen)
            elif WITH_PASSES and recording:
                add_to(record, branch, seen)
        if tau < 1.0 or (coated and coat.roughness > SHARP_ROUGHNESS):  # a coat's glint
            model = terminator_model(frame.options[OPTION_BUMP_TERMINATOR],
                                     mats.bump_rule[material])  # fmt: skip
            point = ShadingPoint(outside, n_diffuse, scale(d, -1.0), n_smooth, model)
            opacity = 1.0 - tau
            if coated:  # the coat's glint is not under the glass's share: the rest is
                kd = scale(kd, opacity)
                phong = Phong(kd, here.ks, here.shininess, here.gloss, n_shading,
                              scale(under, opacity), coat_glint(coat), n_coat,
                              here.diffuse_roughness)  # fmt: skip
                opacity = 1.0
            else:
                phong = Phong(kd, here.ks, here.shininess, here.gloss, n_shading,
                              (1.0, 1.0, 1.0), NO_GLINT, n_coat,
                              here.diffuse_roughness)  # fmt: skip
            local = light_at_point(frame, lights, geo, surf, mats, ws, point, phong, p,
                                   n_geometric, key, event, first and split,
                                   refraction_passes)  # fmt: skip
            seen = mul(w, scale(local, opacity))
            colour = add(colour, seen)
            if WITH_PASSES and first:
                terms = stacks.terms
                glints = here.ks if here.gloss.alpha == 0.0 and not coated else (1.0, 1.0, 1.0)
                record_lighting(record, terms, local, kd, glints, frame.ambient, opacity, split)
            elif WITH_PASSES and recording:
                add_to(record, branch, seen)
        if WITH_TRANSLUCENT and max(here.translucent) > 0.0:  # light from the other side
            share = mul(scale(here.translucent, 1.0 - tau), under)  # as kd's
            through = translucent_light(frame, lights, geo, surf, mats, ws, share, p, n_shading,
                                        n_geometric, o, d, key, event,
                                        refraction_passes)  # fmt: skip
            seen = mul(w, through)
            colour = add(colour, seen)
            if WITH_PASSES and first and split:
                add_to(record, REC_DIFFUSE, through)  # Cycles' Diffuse passes hold it
            elif WITH_PASSES and recording and not first:
                add_to(record, branch, seen)
        event += 1
        straight = here.transparent
        if (
            straight[0] > 0.0 or straight[1] > 0.0 or straight[2] > 0.0
        ) and crossed < MAX_CROSSINGS:
            # What passes straight through: on from the far side, unbent, no bounce counted
            beyond = spawn_point(p, scale(n_geometric, -1.0), o)
            onward = REC_REFRACTION if depth == 0 else branch
            top = _push(rays, top, beyond, d, mul(w, straight), depth, onward, refracted_before,
                        beyond_medium, crossed + 1, refractions)  # fmt: skip
        if depth >= max_depth:
            continue
        spread, samples = _glossy_samples(frame, here, depth, rho, coat_reflects, tau)
        for sample in range(samples):
            top = _leave_surface(
                rays, top, here, sample, samples, spread, key, event, o, d, w_below, p,
                n_shading, n_geometric, outside, cos_i, tau, rho, coat_reflects, coat_colour,
                entering, depth, branch, medium, beyond_medium, refractions,
            )  # fmt: skip
        if coated:
            spread, samples = _clear_coat_samples(frame, coat, depth, coat_reflects_all)
            for sample in range(samples):
                top = _leave_clear_coat(rays, top, coat, n_coat, sample, samples, spread, key,
                                        event, d, w, outside, n_geometric, depth,
                                        branch, medium, refractions)  # fmt: skip
    return colour, alpha
