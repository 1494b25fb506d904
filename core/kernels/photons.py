"""Caustic photons: the light of the lights in Blender's units carried by mirrors and glass
onto diffuse surfaces (paths light -> specular+ -> diffuse), which shadow rays cannot
follow: a shadow ray goes straight to the light, so a glass ball's focus and a mirror's
sun patch are missing from a Whitted picture without them.

Where photons start (the "caster hulls"). Only light that meets a mirror or glass can
become a caustic, so photons are aimed at the convex hulls (a sphere or a box,
core.kernels.caster_hulls) of the shapes whose material reflects or refracts
(core.compile.caustics), not sprayed over the scene. A photon of (light l, hull k) starts at
a point x of hull k's surface (normal n, drawn with density p(x) per unit area) and samples
light l from x exactly as a shading point does (`emitters.emitter_sample`): direction L,
distance t and weight w, with the light's table radiance R (core.kernels.emitters: a
shading point's irradiance is pi (n.L) R w on average). Every light ray that enters the
convex hull crosses its surface once, with n.L > 0 there, so the power entering it is the
integral of that irradiance over its surface: a photon carries

    pi R w (n.L) v / (p(x) N c)

for N photons of its row, v the shadow ray's transmittance from x to the light (light that
reached x through other glass comes as that glass's own photons), and c the number of hulls
the light ray enters before its first hit (the same ray, sampled from each hull it crosses,
counts once in all). It then travels from x along -L. A light inside the hull (a lamp in a
glass globe) sends every ray out through it once: x is drawn over the whole hull, n.L < 0,
and the photon starts at the light's sample, its way to x (through the globe) traced, not
shadow-tested.

How it travels. At each hit the material's terms (its row of the table: reflectivity and
mirror tint, transparency with the exact Fresnel reflectance, glass tints, what passes
straight) give the reflected, refracted and straight-on weights the integrator gives a
camera ray (core.kernels.integrator); one branch is chosen with probability of its mean
weight (Russian roulette: the rest is absorbed), and the photon's power is divided by that
probability, so the estimate stays unbiased. On a rough surface, with Glossy Samples, the
facet it meets is drawn from the GGX lobe as a camera ray's is (core.kernels.glossy), and a
photon it sends below the surface is lost. A photon that has reflected or refracted at
least once is stored where it meets a surface with a diffuse part (its incident power,
position and direction); the shading point multiplies in its own colour
(core.kernels.caustics). Light that passes straight (Transparent BSDF, Alpha) is not a
caustic: shadow rays see it. Inside an object whose material absorbs, a photon keeps
exp(-sigma t) of its power over the length t it travels there (core.kernels.absorption).
A node material whose terms vary over the surface (a textured
chrome, a glass whose colour or mix follows Fresnel or Layer Weight, a textured floor) has
them from its program at each hit, as camera rays do: its reflection and refraction carry
photons on, and a photon it receives is stored with the incident power, the shading point's
program giving the diffuse colour.

The report's lights (CS488 point and area lights with their falloff 1 / (c0 + c1 d + c2 d^2),
and directional lights) send photons too, numbered after the lights in Blender's units:
points, then areas, then suns. A point of theirs lights x as a point source of intensity I
of physical falloff, I cos / t^2: a photon of power pi I (n.L) v / (t^2 p(x) N c), the pi
undoing the gather's Lambertian 1 / pi, since the report's diffuse term is kd I cos. Where
the photon is stored, after a path of length D from the light, its power is multiplied by
D^2 / (c0 + c1 D + c2 D^2): the report's falloff along the unfolded path, so that a flat
mirror lights the floor exactly as the light's mirror image would by the report's formula
(tested). An area light's point is uniform over its rectangle, as its shadow rays' points
are; a directional light has no falloff.

Every number comes from the photon's own key (seed, row, index), so the photons are the
same for any threads, tiles or farm split.
"""

import math

import numpy as np

from ..jit.decorators import kernel
from .absorption import NO_MEDIUM, absorbed, medium_beyond
from .bent_normal import kept_above
from .caster_hulls import hull_centre, hull_point, hull_start, hulls_entered, start_density
from .emitters import emitter_sample
from .fresnel import fresnel_dielectric
from .glossy import visible_normal
from .integrator import channel_mean, mirror_tint, refract
from .layout import EMITS_FROM_SURFACE
from .light_mesh import SHORT_OF_SURFACE
from .light_pyramid import TRAVERSE_ALL
from .material_at_hit import run_program_at
from .options import (
    EMITTER_FACING_DISK,
    EMITTER_MESH,
    EMITTER_SPHERE,
    EMITTER_SUN_CONE,
    EMITTER_SUN_DISK,
)
from .rng import PURPOSE_PHOTON, chain, uniform2
from .shader_program import ray_at
from .shading import AreaLight, square_to_light
from .shadow_log import begin_point
from .surface import surface_at
from .surface_terms import table_surface, terms_from_lobes
from .trace import closest_hit, spawn_point, transmittance
from .vec import add, dot, mul, normalize, row, scale, sub

# PhotonTally slots: what a photon pass counts, for the compile's report
TALLY_STORED = 0  # photons stored on diffuse surfaces
TALLY_DROPPED = 1  # stored photons beyond the arrays' room
TALLY_SLOTS = 2

# A light with extent (`_has_extent`) draws this share of its photons' starts facing its
# centre, the rest over the whole hull (core.kernels.caster_hulls.start_density)
FACING_SHARE = 0.75

NO_FALLOFF = (0.0, 0.0, 1.0)  # c0 c1 c2 of a light whose photons carry its falloff already

# Branch switches (core.compile.caustics): which specular events may carry a photon
REFLECTIVE, REFRACTIVE = 1, 2


@kernel
def _report_light(lights, light):
    """(0 point, 1 area, 2 directional; its row) of the report's light numbered `light`."""
    j = light - lights.emitter_kind.shape[0]
    points, areas = lights.point_position.shape[0], lights.area_centre.shape[0]
    if j < points:
        return 0, j
    if j < points + areas:
        return 1, j - points
    return 2, j - points - areas


@kernel
def _report_light_sample(lights, light, x, a, b):
    """(unit direction from x to the light, distance, intensity, falloff c0 c1 c2) of the
    report's light numbered `light`; an area light's point (a, b) of its rectangle."""
    kind, j = _report_light(lights, light)
    if kind == 2:
        return row(lights.sun_toward, j), math.inf, row(lights.sun_intensity, j), NO_FALLOFF
    if kind == 0:
        position = row(lights.point_position, j)
        intensity, falloff = row(lights.point_intensity, j), row(lights.point_attenuation, j)
    else:
        area = AreaLight(row(lights.area_centre, j), row(lights.area_edge_u, j),
                         row(lights.area_edge_v, j))  # fmt: skip
        position = square_to_light(area, a, b)  # as its shadow rays' points
        intensity, falloff = row(lights.area_intensity, j), row(lights.area_attenuation, j)
    gap = sub(position, x)
    t = math.sqrt(dot(gap, gap))
    if t == 0.0:
        return gap, 0.0, intensity, falloff
    return scale(gap, 1.0 / t), t, intensity, falloff


@kernel
def falloff_share(falloff, distance):
    """D^2 / (c0 + c1 D + c2 D^2): the report's falloff over a path of length D, against the
    physical 1 / D^2 the photons' density carries; 1 for lights without it (NO_FALLOFF)."""
    c0, c1, c2 = falloff
    if c0 == 0.0 and c1 == 0.0:
        return 1.0 / c2
    return distance * distance / (c0 + c1 * distance + c2 * distance * distance)


@kernel
def _light_axis(lights, light, centre):
    """The unit direction from `centre` towards the light (a sun's own; an emissive
    surface's first triangle's centre; a report's light's position or centre)."""
    if light >= lights.emitter_kind.shape[0]:
        kind, j = _report_light(lights, light)
        if kind == 2:
            return row(lights.sun_toward, j)
        target = row(lights.point_position if kind == 0 else lights.area_centre, j)
        return normalize(sub(target, centre))
    kind = lights.emitter_kind[light]
    if kind >= EMITTER_SUN_CONE and kind != EMITTER_MESH:
        return row(lights.emitter_position, light)
    if kind == EMITTER_MESH:
        first = int(lights.emitter_param[light, 0])
        corners = lights.glow_triangles
        target = (
            (corners[first, 0] + corners[first, 3] + corners[first, 6]) / 3.0,
            (corners[first, 1] + corners[first, 4] + corners[first, 7]) / 3.0,
            (corners[first, 2] + corners[first, 5] + corners[first, 8]) / 3.0,
        )
    else:
        target = row(lights.emitter_position, light)
    return normalize(sub(target, centre))


@kernel
def _has_extent(lights, light):
    """Whether the light's rays reach a hull from more than one point (an area light, a
    sphere with a radius, a sun with an angle, a glowing surface): then a hull's points
    facing away from the light's centre may be lit."""
    if light >= lights.emitter_kind.shape[0]:
        kind, _ = _report_light(lights, light)
        return kind == 1  # the report's area light
    kind = lights.emitter_kind[light]
    if kind in (EMITTER_SPHERE, EMITTER_FACING_DISK, EMITTER_SUN_CONE, EMITTER_SUN_DISK):
        return lights.emitter_param[light, 0] > 0.0  # a radius; a sun's 1 - cos(half angle)
    return True  # a panel, a glowing surface


@kernel
def photon_start(geo, lights, casters, containing, light, k, key, photons, stacks):
    """(start point, unit direction of travel, distance from the light to the hull, power,
    falloff) of one photon of row (light, hull k) of `photons` photons, before the share of
    the hulls its light ray enters and the report's falloff (`falloff_share`); power 0 when
    its light sample brings nothing there. The hull's point is drawn facing the light
    (core.kernels.caster_hulls), its density divided out, and the photon starts there; for
    a light inside the hull (`containing`), over the whole hull, and the photon starts at
    the light, its path to the hull traced rather than shadow-tested."""
    a, b = uniform2(key, PURPOSE_PHOTON, 0, 0)
    pick, choose = uniform2(key, PURPOSE_PHOTON, 0, 1)
    inside = containing[light, k] != 0
    if inside:
        x, n, density = hull_point(casters, k, a, b, pick)
    else:
        axis = _light_axis(lights, light, hull_centre(casters, k))
        if not _has_extent(lights, light):
            x, n, density = hull_start(casters, k, axis, a, b, pick)
        else:  # it lights points facing away from its centre too (core.kernels.caster_hulls)
            if choose < FACING_SHARE:
                x, n, _ = hull_start(casters, k, axis, a, b, pick)
            else:
                x, n, _ = hull_point(casters, k, a, b, pick)
            density = start_density(casters, k, axis, n, FACING_SHARE)
    a, b = uniform2(key, PURPOSE_PHOTON, 1, 0)
    short = 1.0
    if light < lights.emitter_kind.shape[0]:
        to_light, t, weight, tint = emitter_sample(lights, light, x, n, a, b)
        radiance, falloff = mul(row(lights.emitter_radiance, light), tint), NO_FALLOFF
        if lights.emitter_flags[light] & EMITS_FROM_SURFACE:
            short = 1.0 - SHORT_OF_SURFACE
    else:  # the irradiance pi R w of a point source of physical falloff, pi I / t^2
        to_light, t, radiance, falloff = _report_light_sample(lights, light, x, a, b)
        weight = 1.0 / (t * t) if 0.0 < t < math.inf else 1.0
    # the light's rays cross the hull's surface inwards, or (from a light inside) outwards
    cos_n = -dot(n, to_light) if inside else dot(n, to_light)
    if weight <= 0.0 or t == 0.0 or cos_n <= 0.0 or density <= 0.0:
        return x, to_light, t, (0.0, 0.0, 0.0), falloff
    if inside:  # from the light (just short of an emissive surface) towards x
        power = math.pi * weight * cos_n / (density * photons)
        start = add(x, scale(to_light, t * short))
        return start, scale(to_light, -1.0), t, scale(radiance, power), falloff
    begin_point(stacks.shadow_state)  # crossings of varying surfaces count as passing
    visible = transmittance(geo, x, to_light, t * short, stacks, TRAVERSE_ALL)
    power = math.pi * weight * cos_n * visible / (density * photons)
    coloured = mul(radiance, (stacks.shadow_tint[0], stacks.shadow_tint[1], stacks.shadow_tint[2]))
    return x, scale(to_light, -1.0), t, scale(coloured, power), falloff


@kernel
def trace_photons(geo, surf, mats, lights, casters, containing, plan, seed, branches,
                  max_bounces, spread, measure, out_position, out_direction, out_power, stacks,
                  shader_stack, lobes, tally):  # fmt: skip
    """Trace photons of rows of `plan` (light, caster hull, the row's photons, the row's
    number, first, count: photons first to first + count - 1 of the row, so that a pass can
    be traced in parts, the same photons whatever the parts), storing those that reach a
    diffuse surface by way of a mirror or glass into the out_* arrays (position, direction
    of travel, power), in order; returns how many were stored. `branches`: REFLECTIVE |
    REFRACTIVE, the specular events a photon may take; `spread`: rough surfaces scatter
    photons over their lobes (RenderSettings.glossy_samples > 0), else they are sharp;
    `shader_stack` and `lobes`: a workspace's, for node materials' programs.

    `measure`: trace nothing, only add up the mean power (over RGB) each row's photons send
    into its hull, into out_power[row, 0] (zeros on entry), to share a pass's photons among
    the rows (core.compile.caustics). One kernel does both, rather than a second one, so
    that the searches and the light samples it shares with the tracing are optimised and
    made into machine code once: a kernel of its own for this took as long to compile as
    the whole tracer (14 s against 13)."""
    stored = 0
    for r in range(plan.shape[0]):
        light, k, photons, number = plan[r, 0], plan[r, 1], plan[r, 2], plan[r, 3]
        for i in range(plan[r, 4], plan[r, 4] + plan[r, 5]):
            key = chain(chain(chain(np.uint64(0), seed), number), i)
            o, d, t_light, power, falloff = photon_start(geo, lights, casters, containing,
                                                         light, k, key, photons,
                                                         stacks)  # fmt: skip
            if measure:
                out_power[r, 0] += channel_mean(power) * falloff_share(falloff, t_light)
                continue
            if containing[light, k]:
                t_light = 0.0  # it starts at the light
            if max(power[0], power[1], power[2]) <= 0.0:
                continue
            shape, t, part, b1, b2 = closest_hit(geo, o, d, math.inf, stacks)
            # the light ray from the light to its first hit: each hull it enters samples it
            entered = hulls_entered(casters, containing, light, o, d, -t_light,
                                    t if shape >= 0 else math.inf)  # fmt: skip
            power = scale(power, 1.0 / max(entered, 1))
            travelled = t_light  # from the light, for the report's falloff
            specular = False
            medium = NO_MEDIUM  # what it travels in (core.kernels.absorption)
            for bounce in range(max_bounces + 1):
                if shape < 0:
                    break
                travelled += t
                power = absorbed(mats, medium, power, t)
                material = surf.shape_material[shape]
                programmed = mats.shader_range[material, 0] >= 0
                p, n_geometric, n_shading, u, v = surface_at(geo, surf, shape, part, b1, b2, o,
                                                             d, t, programmed)  # fmt: skip
                if programmed:
                    # a node material varying over the surface: its program's terms here, as
                    # a camera ray's (core.kernels.integrator); Light Path: neither a camera
                    # nor a shadow ray, `bounce` bounces
                    ray = ray_at(0.0, 0.0, bounce, p, d, n_geometric)
                    run_program_at(geo, surf, mats, shape, material, part, p, n_shading, u, v,
                                   shader_stack, lobes, ray)  # fmt: skip
                    here = terms_from_lobes(lobes)
                    if here.normal[0] != 0.0 or here.normal[1] != 0.0 or here.normal[2] != 0.0:
                        n_shading = kept_above(n_geometric, d, here.normal)  # Bump, Normal Map
                else:
                    here = table_surface(mats, material, row(mats.diffuse, material))
                tau, rho = here.transparency, here.reflectivity
                # (a translucent surface gathers the photons on its back for its front)
                diffuse = (mats.texture[material] >= 0 or channel_mean(here.kd) > 0.0
                           or channel_mean(here.translucent) > 0.0)  # fmt: skip
                # a varying material's diffuse colour is its program's at each shading point,
                # which multiplies it in (core.kernels.caustics)
                if specular and tau < 1.0 and (diffuse or programmed):
                    if stored < out_power.shape[0]:
                        share = falloff_share(falloff, travelled)
                        for a in range(3):
                            out_position[stored, a] = p[a]
                            out_direction[stored, a] = d[a]
                            out_power[stored, a] = power[a] * share
                        stored += 1
                        tally[TALLY_STORED] += 1
                    else:
                        tally[TALLY_DROPPED] += 1
                entering = dot(d, n_geometric) < 0.0
                if not entering:
                    n_geometric = scale(n_geometric, -1.0)
                    n_shading = scale(n_shading, -1.0)
                # the facet it meets: the shading normal, or on a rough surface (with Glossy
                # Samples, as camera rays) one drawn from its GGX lobe (core.kernels.glossy)
                m = n_shading
                rough = spread and here.roughness > 0.0
                if rough:
                    u1, u2 = uniform2(key, PURPOSE_PHOTON, 2 + bounce, 1)
                    alpha = max(here.roughness * here.roughness, 1e-6)
                    m = visible_normal(scale(d, -1.0), n_shading, alpha, u1, u2)
                cos_i = min(1.0, max(0.0, -dot(d, m)))
                reflect = (0.0, 0.0, 0.0)
                through = (0.0, 0.0, 0.0)
                bent = d
                if branches & REFLECTIVE and rho > 0.0:
                    reflect = scale(mirror_tint(here, cos_i), (1.0 - tau) * rho)
                if tau > 0.0:
                    n1, n2 = ((here.outer_ior, here.inner_ior) if entering
                              else (here.inner_ior, here.outer_ior))  # fmt: skip
                    f, cos_t = fresnel_dielectric(cos_i, n1, n2)
                    if branches & REFLECTIVE:
                        reflect = add(reflect, scale(here.glass_reflect, tau * f))
                    if branches & REFRACTIVE and f < 1.0:
                        lost = f * here.refraction_fresnel
                        through = scale(here.glass_transmit, tau * (1.0 - lost))
                        bent = refract(d, m, n1 / n2, cos_i, cos_t)
                straight = here.transparent
                p_reflect, p_through = channel_mean(reflect), channel_mean(through)
                p_straight = channel_mean(straight)
                total = p_reflect + p_through + p_straight
                if total <= 0.0 or bounce == max_bounces:
                    break
                u, _ = uniform2(key, PURPOSE_PHOTON, 2 + bounce, 0)
                u *= max(total, 1.0)  # past `total` (when below 1) the photon is absorbed
                if u < p_reflect:
                    d = sub(d, scale(m, 2.0 * dot(d, m)))
                    if rough and dot(d, n_geometric) <= 0.0:
                        break  # sent below the surface: shadowed by the facets about it
                    o = spawn_point(p, n_geometric, o)
                    power = scale(mul(power, reflect), 1.0 / p_reflect)
                    specular = True
                elif u < p_reflect + p_through:
                    if rough and dot(bent, n_geometric) >= 0.0:
                        break
                    o = spawn_point(p, scale(n_geometric, -1.0), o)
                    d = bent
                    power = scale(mul(power, through), 1.0 / p_through)
                    specular = True
                    medium = medium_beyond(mats, material, entering, medium)
                elif u < total:
                    o = spawn_point(p, scale(n_geometric, -1.0), o)
                    power = scale(mul(power, straight), 1.0 / p_straight)
                    medium = medium_beyond(mats, material, entering, medium)
                else:
                    break
                power = scale(power, max(total, 1.0))
                shape, t, part, b1, b2 = closest_hit(geo, o, d, math.inf, stacks)
    return stored
