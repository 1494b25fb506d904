"""Whitted's recursion without recursion: the tree of reflected and refracted rays, walked
depth-first with an explicit stack from the `Workspace`.

At each hit of a ray carrying weight w (what its colour counts for in the pixel):

    colour += w (1 - tau) local               local = the report's Phong lighting
    reflected ray, weight w ((1 - tau) rho + tau F)
    refracted ray, weight w tau (1 - F)

with rho the material's reflectivity, tau its transparency and F the exact dielectric
Fresnel reflectance for the indices on the two sides (outer and inner IOR, swapped when the
ray leaves the object); past the critical angle F = 1 (total internal reflection). Rays stop
after `max_depth` bounces, or once their weight can no longer show (MIN_WEIGHT).
"""

import math

from ..jit import inlined_kernel, kernel
from .emitters import emitted_colour
from .emitters_seen import emitters_seen
from .environment import environment_light, environment_seen
from .layout import ENVIRONMENT_NONE
from .options import (
    OPTION_ENVIRONMENT,
    OPTION_MAX_DEPTH,
    OPTION_PASSES,
    OPTION_TRANSPARENT,
    PASSES_LIGHT_SPLIT,
    PASSES_UV,
)
from .pass_record import (
    REC_ENVIRONMENT,
    REC_REFLECTION,
    REC_REFRACTION,
    add_to,
    clear,
    record_hit,
    record_lighting,
)
from .shading import Phong, ShadingPoint, local_colour
from .surface import diffuse_colour, surface_at
from .trace import closest_hit, spawn_point
from .vec import add, dot, mul, normalize, row, scale, sub
from .workspace import RAYS_TRACED

MIN_WEIGHT = 1e-6


@kernel
def fresnel_dielectric(cos_i, n1, n2):
    """(reflectance F, cos of the refracted angle) for light going from index n1 into n2 at
    incidence cos_i in [0, 1]: the unpolarised average of the exact s and p reflectances.
    Total internal reflection gives (1, 0)."""
    eta = n1 / n2
    sin2_t = eta * eta * max(0.0, 1.0 - cos_i * cos_i)
    if sin2_t >= 1.0:
        return 1.0, 0.0
    cos_t = math.sqrt(1.0 - sin2_t)
    rs = (n1 * cos_i - n2 * cos_t) / (n1 * cos_i + n2 * cos_t)
    rp = (n1 * cos_t - n2 * cos_i) / (n1 * cos_t + n2 * cos_i)
    return 0.5 * (rs * rs + rp * rp), cos_t


@kernel
def refract(d, n, eta, cos_i, cos_t):
    """Snell's law: unit d through the surface with unit normal n facing the incoming ray,
    eta = n1 / n2, cos_i = -d.n and cos_t from `fresnel_dielectric`."""
    return normalize(add(scale(d, eta), scale(n, eta * cos_i - cos_t)))


@kernel
def _push(rays, top, o, d, w, depth, branch, refracted):
    if max(w[0], w[1], w[2]) < MIN_WEIGHT:
        return top
    for a in range(3):
        rays.origin[top, a] = o[a]
        rays.direction[top, a] = d[a]
        rays.weight[top, a] = w[a]
    rays.depth[top] = depth
    rays.branch[top] = branch
    rays.refracted[top] = refracted
    return top + 1


@inlined_kernel
def trace_ray(ps, o, d, key, ws):
    """(linear RGB colour seen along unit direction d from o, with every bounce; its alpha:
    0 for a camera ray that meets nothing under Film > Transparent, or meets a holdout,
    else 1). When passes are made, ws.record gets what they need of this camera ray
    (core.kernels.pass_record): each ray's colour goes to the term of its branch, the
    camera ray's own hit is split into ambient, diffuse and specular."""
    frame, geo, surf, mats, lights = ps
    stacks, rays, record = ws.stacks, ws.rays, ws.record
    max_depth = frame.options[OPTION_MAX_DEPTH]
    passes = frame.options[OPTION_PASSES]
    recording = passes != 0
    split = (passes & PASSES_LIGHT_SPLIT) != 0
    with_uv = (passes & PASSES_UV) != 0
    if recording:
        clear(record, 0.0)
    colour = (0.0, 0.0, 0.0)
    alpha = 1.0
    top = _push(rays, 0, o, d, (1.0, 1.0, 1.0), 0, REC_ENVIRONMENT, 0)
    event = 0
    while top > 0:
        top -= 1
        o, d = row(rays.origin, top), row(rays.direction, top)
        w, depth, branch = row(rays.weight, top), rays.depth[top], rays.branch[top]
        came_through = rays.refracted[top] != 0  # left its last surface by refraction
        stacks.ray_counts[RAYS_TRACED] += 1
        shape, t, part, b1, b2 = closest_hit(geo, o, d, math.inf, stacks)
        if depth > 0 and lights.emitter_kind.shape[0] > 0:
            # Lights in Blender's units, seen in mirrors and through glass
            glimpse = emitters_seen(lights, o, d, t if shape >= 0 else math.inf, came_through)
            if glimpse[0] > 0.0 or glimpse[1] > 0.0 or glimpse[2] > 0.0:
                seen = mul(w, glimpse)
                colour = add(colour, seen)
                if recording:
                    add_to(record, branch, seen)
        if shape < 0:
            if depth == 0 and frame.options[OPTION_TRANSPARENT] != 0:
                alpha = 0.0  # the camera ray itself: nothing there, not even background
            else:
                seen = mul(w, environment_seen(frame, lights, d, depth, came_through))
                colour = add(colour, seen)
                if recording:
                    add_to(record, branch, seen)
            continue
        if depth == 0 and surf.shape_holdout[shape] != 0:
            alpha = 0.0  # a hole in the picture, as Cycles cuts: nothing behind shows
            continue
        material = surf.shape_material[shape]
        first = recording and depth == 0
        textured = mats.texture[material] >= 0
        p, n_geometric, n_shading, u, v = surface_at(
            geo, surf, shape, part, b1, b2, o, d, t, textured or (first and with_uv)
        )
        tau = mats.transparency[material]
        rho = mats.reflectivity[material]
        # Face the side the ray came from
        entering = dot(d, n_geometric) < 0.0
        if not entering:
            n_geometric = scale(n_geometric, -1.0)
            n_shading = scale(n_shading, -1.0)
        outside = spawn_point(p, n_geometric, o)
        kd = diffuse_colour(mats, material, u, v) if tau < 1.0 or first else (0.0, 0.0, 0.0)
        if first:
            record_hit(record, surf, mats, shape, material, p, n_shading, u, v, 1.0 - tau, kd)
        if tau < 1.0:
            point = ShadingPoint(outside, n_shading, scale(d, -1.0))
            ks = row(mats.specular, material)
            phong = Phong(kd, ks, mats.shininess[material])
            splitting = first and split
            local = local_colour(frame, lights, geo, stacks, point, phong, key, event, splitting)
            if lights.emitter_kind.shape[0] > 0:  # lights in Blender's units
                emitted = emitted_colour(
                    frame, lights, geo, stacks, point, phong, key, event, splitting
                )
                local = add(local, emitted)
            if frame.options[OPTION_ENVIRONMENT] != ENVIRONMENT_NONE:  # the World's light
                sky = environment_light(
                    frame, lights, geo, stacks, point, kd, key, event, splitting
                )
                local = add(local, sky)
            seen = mul(w, scale(local, 1.0 - tau))
            colour = add(colour, seen)
            if first:
                terms = stacks.terms
                record_lighting(record, terms, local, kd, ks, frame.ambient, 1.0 - tau, split)
            elif recording:
                add_to(record, branch, seen)
        event += 1
        if depth >= max_depth:
            continue
        cos_i = min(1.0, max(0.0, -dot(d, n_shading)))
        reflect_weight = (1.0 - tau) * rho
        if tau > 0.0:
            outer, inner = mats.ior[material, 0], mats.ior[material, 1]
            n1, n2 = (outer, inner) if entering else (inner, outer)
            f, cos_t = fresnel_dielectric(cos_i, n1, n2)
            reflect_weight += tau * f
            if f < 1.0:
                refracted = refract(d, n_shading, n1 / n2, cos_i, cos_t)
                inside = spawn_point(p, scale(n_geometric, -1.0), o)
                through = REC_REFRACTION if depth == 0 else branch
                weight = scale(w, tau * (1.0 - f))
                top = _push(rays, top, inside, refracted, weight, depth + 1, through, 1)
        if reflect_weight > 0.0:
            reflected = sub(d, scale(n_shading, 2.0 * dot(d, n_shading)))
            mirrored = REC_REFLECTION if depth == 0 else branch
            weight = scale(w, reflect_weight)
            top = _push(rays, top, outside, reflected, weight, depth + 1, mirrored, 0)
    return colour, alpha
