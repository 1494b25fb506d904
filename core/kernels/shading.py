"""The report's lighting model at one surface point: ambient + per light diffuse and Phong.

    colour = kd * ambient
           + sum over lights of (kd (N.L) + ks (R.V)^p) * I / (c0 + c1 d + c2 d^2) * visibility

A point light's visibility is its shadow ray's transmittance (0 behind an opaque object).
An area light is the average of that sum over points spread on its rectangle: N shadow
rays, one in each of N equal-area cells ("stratified"), at N independent random points
("uniform", the report's way), or at the first N Halton points shifted by one random offset
per shading point (Cranley-Patterson rotation: "halton"). A light contributes only where N.L > 0.

With adaptive soft shadows an area light's probes decide first whether its samples' rays
are cast (core.kernels.shadow_rays). An area light's shadow rays test only the shapes whose
boxes meet the pyramid from the point to the light, listed once per point
(`core.kernels.light_pyramid`); with none listed the light is unobstructed and no ray is
tested. The pixels are the same as with every shape tested (OPTION_SHADOW_CULLING off, kept
to show that).
"""

import math
from typing import NamedTuple

from ..jit.decorators import inlined_kernel, kernel
from .bent_normal import terminator_term
from .light_pyramid import TRAVERSE_ALL, build_pyramid, pyramid_candidates
from .light_samples import light_spread, square_point
from .options import (
    OPTION_SHADOW_ADAPTIVE,
    OPTION_SHADOW_CULLING,
    OPTION_SHADOW_PATTERN,
    OPTION_SHADOW_SAMPLES,
    SHADOW_HALTON,
)
from .pass_record import TERM_ROW_LIT, TERM_ROW_UNSHADOWED
from .rng import PURPOSE_LIGHT_SHIFT, uniform2
from .shadow_rays import PROBES, light_visibility, probe_square, shadow_visibility
from .vec import add, as_tuple, dot, mul, row, scale, sub
from .workspace import OCCLUDER_POSITION, OCCLUDER_SHAPE

# The largest attenuation factor 1 / (c0 + c1 d + c2 d^2) applied
MAX_FALLOFF = 1e20


# Records rather than runs of scalars, so that an argument put in the wrong place does not
# compile: numba passes a named tuple's fields as it would the scalars, and once inlined they
# cost nothing (the final scene renders in the same time, the same bits)
class ShadingPoint(NamedTuple):
    """Where a surface is lit: shadow rays start at `origin` (the hit point lifted off the
    surface); `normal` is the unit shading normal of its diffuse (and of the report's Phong
    highlight), facing `to_viewer`; `smooth_normal` the surface's own before a Bump or
    Normal Map bent it, and `terminator` the TERMINATOR_* rule (core.vocabulary) of the
    diffuse's shadow terminator term (bent_normal.terminator_term)."""

    origin: tuple
    normal: tuple
    to_viewer: tuple
    smooth_normal: tuple
    terminator: int


class Phong(NamedTuple):
    """The report's material terms: diffuse kd, specular ks (RGB) and the Phong exponent;
    and a node material's rough lobes, which glint in Blender's lights instead
    (core.kernels.microfacet.Gloss; alpha 0 for the report's materials), about
    `gloss_normal` (the shading normal kept from reflecting into the surface, which a bent
    one may be: core.kernels.bent_normal; the diffuse keeps the bent one, as in Cycles).
    Under a clear coat (core.kernels.clear_coat) the glints are times `under` (kd already
    is), and the coat's own rough lobe glints about its normal (alpha 0: none). A rough
    diffuse (`diffuse_roughness` > 0) reflects Blender's lights and World by Oren-Nayar
    (core.kernels.rough_diffuse) where kd stands for Lambert's."""

    kd: tuple
    ks: tuple
    shininess: float
    gloss: tuple
    gloss_normal: tuple
    under: tuple
    coat_gloss: tuple
    coat_normal: tuple
    diffuse_roughness: float


class AreaLight(NamedTuple):
    """A rectangle light's centre and its two edges, the rectangle being
    centre + a edge_u + b edge_v for a, b in [-1/2, 1/2]."""

    centre: tuple
    edge_u: tuple
    edge_v: tuple


@inlined_kernel
def _aim(targets, j, position, origin):
    """Store in targets[j] the unit direction from origin to a light point and the distance."""
    to_light = sub(position, origin)
    distance = math.sqrt(dot(to_light, to_light))
    targets[j, 3] = distance
    if distance > 0.0:
        light_dir = scale(to_light, 1.0 / distance)
        targets[j, 0], targets[j, 1], targets[j, 2] = light_dir


@inlined_kernel
def seen_through(stacks, j):
    """What sample j's shadow ray let through, per channel: stacks.visibility[j] times its
    colour (stacks.visibility_tint, 1 but through coloured transparent surfaces)."""
    v, tint = stacks.visibility[j], stacks.visibility_tint
    return tint[j, 0] * v, tint[j, 1] * v, tint[j, 2] * v


@inlined_kernel
def _lit_by(targets, stacks, j, intensity, attenuation, point, phong):
    """What light point j of `targets` (aimed at by `_aim`, seen through its shadow ray)
    adds at a point."""
    distance = targets[j, 3]
    if distance == 0.0:
        return 0.0, 0.0, 0.0
    radiance = _radiance(intensity, attenuation, distance)
    return _phong_lit(row(targets, j), radiance, seen_through(stacks, j), point, phong)


@inlined_kernel
def _radiance(intensity, attenuation, distance):
    """A light's intensity at `distance`, after the falloff 1 / (c0 + c1 d + c2 d^2)."""
    c0, c1, c2 = attenuation
    # Without c0 the falloff grows without bound at the light: cap it, so a surface touching
    # a light is blinding but finite (found by the fuzzer: 1 / (c2 d^2) overflowed)
    falloff = 1.0 / max(c0 + c1 * distance + c2 * distance * distance, 1.0 / MAX_FALLOFF)
    return scale(intensity, falloff)


@inlined_kernel
def add_falling(terms, light_dir, radiance, visible, n, weight):
    """Add to `terms` (core.kernels.pass_record) the light falling on the point (times N.L
    and `weight`, RGB: what the diffuse makes of it beyond kd, as Cycles' Diffuse Direct
    holds the diffuse's light over its colour) with and without what its shadow ray let
    through (`visible`, RGB). For the shadow and diffuse passes of a first hit only: the
    colour itself is `_phong_lit`'s."""
    n_dot_l = dot(n, light_dir)
    if n_dot_l > 0.0:
        for a in range(3):
            falling = radiance[a] * n_dot_l * weight[a]
            terms[TERM_ROW_UNSHADOWED, a] += falling
            terms[TERM_ROW_LIT, a] += falling * visible[a]


@inlined_kernel
def _phong_lit(light_dir, radiance, visible, point, phong):
    """The report's Phong terms for light arriving along unit light_dir with `radiance`,
    of which `visible` (RGB) gets through (the shadow ray's transmittance)."""
    n, to_viewer = point.normal, point.to_viewer
    kd, ks, shininess = phong.kd, phong.ks, phong.shininess
    n_dot_l = dot(n, light_dir)
    if n_dot_l <= 0.0 or visible[0] == visible[1] == visible[2] == 0.0:
        return 0.0, 0.0, 0.0
    reflectance = scale(
        kd, n_dot_l * terminator_term(point.smooth_normal, n, light_dir, point.terminator)
    )
    if ks[0] > 0.0 or ks[1] > 0.0 or ks[2] > 0.0:
        # Unit length already: n and light_dir are unit vectors
        reflected = sub(scale(n, 2.0 * n_dot_l), light_dir)
        # Rounding can put R.V a hair above 1, and (1 + 2e-16)^1e300 is infinite (fuzzer)
        r_dot_v = min(dot(reflected, to_viewer), 1.0)
        if r_dot_v > 0.0:
            reflectance = add(reflectance, scale(ks, r_dot_v**shininess))
    return mul(reflectance, mul(radiance, visible))


@kernel
def light_candidates(geo, stacks, origin, area):
    """List in stacks.candidates the shapes that may stand between `origin` and the area
    light; returns their count or TRAVERSE_ALL. Finds the cached occluder in the list."""
    build_pyramid(stacks.pyramid, origin, area.centre, area.edge_u, area.edge_v)
    count = pyramid_candidates(geo, stacks.pyramid, stacks.candidates, stacks.top)
    occluder = stacks.occluder
    occluder[OCCLUDER_POSITION] = -1
    for c in range(count):
        if stacks.candidates[c] == occluder[OCCLUDER_SHAPE]:
            occluder[OCCLUDER_POSITION] = c
    return count


@inlined_kernel
def square_to_light(area, a, b):
    """The area light's point for the unit square's (a, b)."""
    return add(area.centre, add(scale(area.edge_u, a - 0.5), scale(area.edge_v, b - 0.5)))


@kernel
def local_colour(frame, lights, geo, stacks, point, phong, key, event, split):
    """Colour at a `ShadingPoint` of a surface with `Phong` terms. `key` and `event` select
    the area lights' random numbers. With `split` (a camera ray's first hit, when the
    diffuse, specular or shadow pass is made) stacks.terms also gets the light falling on
    the point, with and without shadows.

    Each light aims its points into stacks.light_targets, `shadow_visibility` casts their
    shadow rays, and only then are the Phong terms summed, in a loop with no call in it."""
    targets, terms = stacks.light_targets, stacks.terms
    origin, n = point.origin, point.normal
    if split:
        terms[:] = 0.0
    colour = mul(phong.kd, as_tuple(frame.ambient))
    for light in range(lights.sun_toward.shape[0]):
        toward = row(lights.sun_toward, light)
        targets[0, 0], targets[0, 1], targets[0, 2] = toward
        targets[0, 3] = math.inf
        shadow_visibility(geo, stacks, TRAVERSE_ALL, origin, n, 0, 1)
        radiance = row(lights.sun_intensity, light)
        seen = seen_through(stacks, 0)
        colour = add(colour, _phong_lit(toward, radiance, seen, point, phong))
        if split:
            add_falling(terms, toward, radiance, seen, n, (1.0, 1.0, 1.0))
    for light in range(lights.point_position.shape[0]):
        _aim(targets, 0, row(lights.point_position, light), origin)
        shadow_visibility(geo, stacks, TRAVERSE_ALL, origin, n, 0, 1)
        intensity = row(lights.point_intensity, light)
        attenuation = row(lights.point_attenuation, light)
        colour = add(colour, _lit_by(targets, stacks, 0, intensity, attenuation, point, phong))
        if split and targets[0, 3] != 0.0:
            radiance = _radiance(intensity, attenuation, targets[0, 3])
            add_falling(terms, row(targets, 0), radiance, seen_through(stacks, 0), n,
                        (1.0, 1.0, 1.0))  # fmt: skip
    samples = frame.options[OPTION_SHADOW_SAMPLES]
    pattern = frame.options[OPTION_SHADOW_PATTERN]
    adaptive = frame.options[OPTION_SHADOW_ADAPTIVE] != 0
    for light in range(lights.area_centre.shape[0]):
        area = AreaLight(
            row(lights.area_centre, light),
            row(lights.area_edge_u, light),
            row(lights.area_edge_v, light),
        )
        stream = event * 65536 + light
        shift = (0.0, 0.0)
        if pattern == SHADOW_HALTON:
            shift = uniform2(key, PURPOSE_LIGHT_SHIFT, stream, 0)
        spread = light_spread(stacks.light_strata, pattern, samples, stream)
        for j in range(samples + PROBES if adaptive else samples):  # the samples, the probes
            if j < samples:
                a, b = square_point(pattern, samples, j, key, stream, shift, spread)
            else:
                a, b = probe_square(-1, j - samples)
            _aim(targets, j, square_to_light(area, a, b), origin)
        listed = TRAVERSE_ALL
        if frame.options[OPTION_SHADOW_CULLING]:
            listed = light_candidates(geo, stacks, origin, area)
        light_visibility(geo, stacks, listed, origin, n, samples, adaptive)
        intensity = row(lights.area_intensity, light)
        attenuation = row(lights.area_attenuation, light)
        total = (0.0, 0.0, 0.0)
        for j in range(samples):
            total = add(total, _lit_by(targets, stacks, j, intensity, attenuation, point, phong))
        colour = add(colour, scale(total, 1.0 / samples))
        if split:
            for j in range(samples):
                distance = targets[j, 3]
                if distance != 0.0:
                    radiance = _radiance(intensity, attenuation, distance)
                    light_dir = row(targets, j)
                    seen = seen_through(stacks, j)
                    share = 1.0 / samples
                    add_falling(terms, light_dir, radiance, seen, n, (share, share, share))
    return colour
