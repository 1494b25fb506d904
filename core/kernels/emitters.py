"""Lights in Blender's units at one surface point: each light's samples, their shadow rays,
and the report's Lambert and Phong terms for what arrives (or, for a node material's rough
lobes, their microfacet glint: core.kernels.microfacet).

For light l seen from a shading point, sample j gives a unit direction L_j, the distance to
the light along it and a weight w_j (`light_sphere`, `light_panel`, `light_sun`); with the
table's radiance R_l (emitter_radiance) the point's colour gains

    sum over lights of  1/N sum_j  (kd (N.L_j) [diffuse] + ks (R_j.V)^p [specular]) R_l w_j v_j

v_j the shadow ray's transmittance (1 when the light casts no shadow), [diffuse] and
[specular] the light's switches. For a white Lambertian surface this is E / pi, Cycles'
brightness. A light that needs no more than one sample (a point without radius, a sun
without angle) gets one, whatever the render's shadow samples.
"""

import math

from ..jit.decorators import kernel
from .bent_normal import on_smooth_side, terminator_term
from .layout import (
    EMITS_DIFFUSE,
    EMITS_FROM_SURFACE,
    EMITS_SHADOW,
    EMITS_SPECULAR,
    EMITS_SPOT,
    EMITS_SPOT_COSINE,
)
from .light_mesh import SHORT_OF_SURFACE, mesh_sample
from .light_panel import panel_sample
from .light_pyramid import TRAVERSE_ALL
from .light_samples import light_spread, square_point
from .light_sphere import facing_disk_sample, sphere_sample, spot_mask
from .light_sun import sun_sample
from .microfacet import gloss_lit
from .options import (
    EMITTER_ELLIPSE,
    EMITTER_FACING_DISK,
    EMITTER_MESH,
    EMITTER_RECTANGLE,
    EMITTER_SPHERE,
    EMITTER_SUN_CONE,
    EMITTER_SUN_DISK,
    OPTION_ROUGH_DIFFUSE,
    OPTION_SHADOW_ADAPTIVE,
    OPTION_SHADOW_CULLING,
    OPTION_SHADOW_PATTERN,
    OPTION_SHADOW_SAMPLES,
    SHADOW_HALTON,
)
from .rng import PURPOSE_LIGHT_SHIFT, uniform2
from .rough_diffuse import beyond_kd, rough_response
from .shading import AreaLight, add_falling, light_candidates, seen_through
from .shadow_rays import PROBES, light_visibility, probe_square
from .vec import add, dot, mul, row, scale, sub

# Random streams of the emitters start here, past any count of the report's area lights
# (whose light l uses stream event * 65536 + l)
EMITTER_STREAM = 32768


@kernel
def _frame_rows(frames, light):
    return (
        (frames[light, 0, 0], frames[light, 0, 1], frames[light, 0, 2]),
        (frames[light, 1, 0], frames[light, 1, 1], frames[light, 1, 2]),
        (frames[light, 2, 0], frames[light, 2, 1], frames[light, 2, 2]),
    )


@kernel
def samples_needed(lights, light, samples):
    """1 for a light every sample of which is the same (a point, a sun without angle)."""
    kind, param = lights.emitter_kind[light], lights.emitter_param
    if kind == EMITTER_MESH:
        return samples
    if kind <= EMITTER_FACING_DISK:
        return 1 if param[light, 0] == 0.0 else samples
    if kind >= EMITTER_SUN_CONE:
        return 1 if param[light, 0] == 0.0 else samples
    return samples


@kernel
def emitter_sample(lights, light, origin, normal, a, b):
    """(unit direction, distance, weight, RGB tint) of light `light`'s sample (a, b) from
    `origin`; distance 0 or weight 0 for a sample that brings nothing. The tint is 1 but
    for an emissive surface whose emission varies (core.kernels.light_mesh)."""
    kind = lights.emitter_kind[light]
    white = (1.0, 1.0, 1.0)
    if kind == EMITTER_MESH:
        return mesh_sample(lights, light, origin, a, b)
    position = row(lights.emitter_position, light)
    param = lights.emitter_param
    if kind >= EMITTER_SUN_CONE:
        toward = sun_sample(
            position, param[light, 0], param[light, 1], kind == EMITTER_SUN_DISK, a, b
        )
        return toward, math.inf, 1.0, white
    if EMITTER_RECTANGLE <= kind <= EMITTER_ELLIPSE:
        edge_u, edge_v, facing = _frame_rows(lights.emitter_frame, light)
        direction, t, weight = panel_sample(
            position, edge_u, edge_v, facing, kind == EMITTER_ELLIPSE, origin, a, b
        )
        return direction, t, weight, white
    radius = param[light, 0]
    if kind == EMITTER_SPHERE:
        direction, t, weight = sphere_sample(position, radius, origin, normal, a, b)
    else:
        direction, t, weight = facing_disk_sample(position, radius, origin, a, b)
    flags = lights.emitter_flags[light]
    if flags & EMITS_SPOT:
        with_cosine = (flags & EMITS_SPOT_COSINE) != 0
        to_light_frame = _frame_rows(lights.emitter_frame, light)
        mask = spot_mask(
            to_light_frame, scale(direction, -1.0), param[light, 1], param[light, 2], with_cosine
        )
        weight *= mask
    return direction, t, weight, white


@kernel
def emitted_colour(frame, lights, geo, stacks, point, phong, key, event, split):
    """The colour the lights in Blender's units give a `ShadingPoint` of a surface with
    `Phong` terms (the module's formula). `key` and `event` select the random numbers; with
    `split` (core.kernels.shading.local_colour's) stacks.terms gets the light falling too."""
    targets, visibility, terms = stacks.light_targets, stacks.visibility, stacks.terms
    origin, n, to_viewer = point.origin, point.normal, point.to_viewer
    kd, ks, shininess, gloss = phong.kd, phong.ks, phong.shininess, phong.gloss
    rough, model = phong.diffuse_roughness, frame.options[OPTION_ROUGH_DIFFUSE]
    glints = gloss.alpha > 0.0
    coat_glints = phong.coat_gloss.alpha > 0.0
    glossy = glints or coat_glints or ks[0] > 0.0 or ks[1] > 0.0 or ks[2] > 0.0
    samples = frame.options[OPTION_SHADOW_SAMPLES]
    pattern = frame.options[OPTION_SHADOW_PATTERN]
    adaptive = frame.options[OPTION_SHADOW_ADAPTIVE] != 0
    colour = (0.0, 0.0, 0.0)
    for light in range(lights.emitter_kind.shape[0]):
        count = samples_needed(lights, light, samples)
        stream = event * 65536 + EMITTER_STREAM + light
        shift = (0.0, 0.0)
        if pattern == SHADOW_HALTON:
            shift = uniform2(key, PURPOSE_LIGHT_SHIFT, stream, 0)
        spread = light_spread(stacks.light_strata, pattern, count, stream)
        # an emissive surface's samples lie on it: the shadow rays stop just short
        short = 1.0 - SHORT_OF_SURFACE if lights.emitter_flags[light] & EMITS_FROM_SURFACE else 1.0
        kind = lights.emitter_kind[light]
        probing = adaptive and kind != EMITTER_MESH  # a mesh's square is its triangles'
        # The samples, then the probes (one call of emitter_sample: each call site is code)
        for j in range(count + PROBES if probing else count):
            if j < count:
                a, b = square_point(pattern, count, j, key, stream, shift, spread)
            else:
                a, b = probe_square(kind, j - count)
            direction, t, weight, tint = emitter_sample(lights, light, origin, n, a, b)
            targets[j, 0], targets[j, 1], targets[j, 2] = direction
            targets[j, 3] = t * short if weight > 0.0 else 0.0
            targets[j, 4] = weight
            targets[j, 5], targets[j, 6], targets[j, 7] = tint
        flags = lights.emitter_flags[light]
        if flags & EMITS_SHADOW:
            listed = TRAVERSE_ALL
            panel = EMITTER_RECTANGLE <= kind <= EMITTER_ELLIPSE
            if panel and frame.options[OPTION_SHADOW_CULLING]:
                frames = lights.emitter_frame
                area = AreaLight(
                    row(lights.emitter_position, light),
                    (frames[light, 0, 0], frames[light, 0, 1], frames[light, 0, 2]),
                    (frames[light, 1, 0], frames[light, 1, 1], frames[light, 1, 2]),
                )
                listed = light_candidates(geo, stacks, origin, area)
            light_visibility(geo, stacks, listed, origin, n, count, probing)
        else:
            for j in range(count):
                visibility[j] = 1.0
                stacks.visibility_tint[j, 0] = 1.0
                stacks.visibility_tint[j, 1] = stacks.visibility_tint[j, 2] = 1.0
        diffuse = 1.0 if flags & EMITS_DIFFUSE else 0.0
        specular = 1.0 if (flags & EMITS_SPECULAR) and glossy else 0.0
        radiance = row(lights.emitter_radiance, light)
        total = (0.0, 0.0, 0.0)
        for j in range(count):
            weight = targets[j, 4]
            if targets[j, 3] == 0.0 or weight == 0.0:
                continue
            light_dir = row(targets, j)
            n_dot_l = dot(n, light_dir)
            if visibility[j] == 0.0:
                continue
            seen = seen_through(stacks, j)
            if kind == EMITTER_MESH:  # a varying emitter's sample's own colour
                seen = mul(seen, (targets[j, 5], targets[j, 6], targets[j, 7]))
            # the glints about their own normals (a bent diffuse normal may face away); the
            # side test only for a surface that glints
            smooth, rule = point.smooth_normal, point.terminator
            if (specular > 0.0 and coat_glints
                    and on_smooth_side(smooth, phong.coat_normal, light_dir, rule)):  # fmt: skip
                glint = gloss_lit(phong.coat_gloss, phong.coat_normal, to_viewer, light_dir)
                total = add(total, mul(glint, scale(seen, weight)))
            if (specular > 0.0 and glints
                    and on_smooth_side(smooth, phong.gloss_normal, light_dir, rule)):  # fmt: skip
                glint = gloss_lit(gloss, phong.gloss_normal, to_viewer, light_dir)
                total = add(total, mul(mul(glint, phong.under), scale(seen, weight)))
            if n_dot_l <= 0.0:
                continue
            term = terminator_term(point.smooth_normal, n, light_dir, point.terminator)
            factor = diffuse * n_dot_l * term
            reflectance = kd
            if rough > 0.0:  # Oren-Nayar: kd's stand-in for this light and view
                reflectance = rough_response(kd, rough, model, n, light_dir, to_viewer)
            if specular > 0.0 and not glints:  # the report's Phong highlight
                reflected = sub(scale(n, 2.0 * n_dot_l), light_dir)
                r_dot_v = min(dot(reflected, to_viewer), 1.0)
                if r_dot_v > 0.0:
                    highlight = r_dot_v**shininess
                    total = add(total, mul(ks, scale(seen, highlight * weight)))
            total = add(total, mul(reflectance, scale(seen, factor * weight)))
            if split and diffuse > 0.0:
                falling = scale(radiance, weight / count)
                add_falling(terms, light_dir, falling, seen, n, beyond_kd(kd, reflectance, term))
        colour = add(colour, scale(mul(total, radiance), 1.0 / count))
    return colour
