"""The report's lighting model at one surface point: ambient + per light diffuse and Phong.

    colour = kd * ambient
           + sum over lights of (kd (N.L) + ks (R.V)^p) * I / (c0 + c1 d + c2 d^2) * visibility

A point light's visibility is its shadow ray's transmittance (0 behind an opaque object).
An area light is the average of that sum over points spread on its rectangle: N shadow
rays, one in each of N equal-area cells ("stratified"), at N independent random points
("uniform", the report's way), or at the first N Halton points shifted by one random offset
per shading point (Cranley-Patterson rotation: "halton"). A light contributes only where N.L > 0.
"""

import math

from core.jit import inlined_kernel, kernel
from core.kernels.options import (
    OPTION_SHADOW_PATTERN,
    OPTION_SHADOW_SAMPLES,
    SHADOW_HALTON,
    SHADOW_STRATIFIED,
)
from core.kernels.rng import PURPOSE_LIGHT, PURPOSE_LIGHT_SHIFT, uniform2
from core.kernels.trace import shadow_transmittance
from core.kernels.vec import add, as_tuple, dot, mul, row, scale, sub
from core.kernels.workspace import SHADOW_RAYS

# The largest attenuation factor 1 / (c0 + c1 d + c2 d^2) applied
MAX_FALLOFF = 1e20


@inlined_kernel
def light_from(
    geo, stacks, position, intensity, attenuation, origin, n, to_viewer, kd, ks, shininess
):
    """What one point emitter at `position` adds at a point (spawned at `origin`)."""
    to_light = sub(position, origin)
    distance = math.sqrt(dot(to_light, to_light))
    if distance == 0.0:
        return 0.0, 0.0, 0.0
    c0, c1, c2 = attenuation
    # Without c0 the falloff grows without bound at the light: cap it, so a surface touching
    # a light is blinding but finite (found by the fuzzer: 1 / (c2 d^2) overflowed)
    falloff = 1.0 / max(c0 + c1 * distance + c2 * distance * distance, 1.0 / MAX_FALLOFF)
    light_dir = scale(to_light, 1.0 / distance)
    return _phong_lit(
        geo, stacks, light_dir, distance, scale(intensity, falloff), origin, n, to_viewer,
        kd, ks, shininess,
    )  # fmt: skip


@inlined_kernel
def _phong_lit(geo, stacks, light_dir, distance, radiance, origin, n, to_viewer, kd, ks, shininess):
    """The report's Phong terms for light arriving along unit light_dir with `radiance`,
    through whatever lies within `distance` (shadow ray)."""
    n_dot_l = dot(n, light_dir)
    if n_dot_l <= 0.0:
        return 0.0, 0.0, 0.0
    stacks.ray_counts[SHADOW_RAYS] += 1
    visible = shadow_transmittance(geo, origin, light_dir, distance, stacks)
    if visible == 0.0:
        return 0.0, 0.0, 0.0
    reflectance = scale(kd, n_dot_l)
    if ks[0] > 0.0 or ks[1] > 0.0 or ks[2] > 0.0:
        # Unit length already: n and light_dir are unit vectors
        reflected = sub(scale(n, 2.0 * n_dot_l), light_dir)
        # Rounding can put R.V a hair above 1, and (1 + 2e-16)^1e300 is infinite (fuzzer)
        r_dot_v = min(dot(reflected, to_viewer), 1.0)
        if r_dot_v > 0.0:
            reflectance = add(reflectance, scale(ks, r_dot_v**shininess))
    return mul(reflectance, scale(radiance, visible))


@kernel
def radical_inverse(i, base):
    """The digits of i in `base` mirrored about the point: the Halton sequence's i-th
    coordinate in that base, in [0, 1)."""
    inverse, scale_ = 0.0, 1.0 / base
    while i > 0:
        inverse += (i % base) * scale_
        i //= base
        scale_ /= base
    return inverse


@kernel
def stratified_cell(j, count):
    """Cell j of `count` equal-area cells tiling the unit square: (x0, y0, width, height).

    Rows of ceil(sqrt(count)) cells; a short last row gets wider cells and a taller row, so
    every cell has area 1/count and the cells cover the square exactly once."""
    columns = int(math.ceil(math.sqrt(count)))
    rows = (count + columns - 1) // columns
    r = j // columns
    in_row = columns if r < rows - 1 else count - columns * (rows - 1)
    height = in_row / count
    y0 = columns * r / count
    return (j - r * columns) / in_row, y0, 1.0 / in_row, height


@kernel
def local_colour(frame, lights, geo, stacks, origin, n, d, kd, ks, shininess, key, event):
    """Colour at a point seen along unit d, with unit shading normal n facing the viewer;
    shadow rays start at `origin` (the point lifted off the surface). `key` and `event`
    select the area lights' random numbers."""
    to_viewer = scale(d, -1.0)
    colour = mul(kd, as_tuple(frame.ambient))
    for light in range(lights.sun_toward.shape[0]):
        colour = add(
            colour,
            _phong_lit(
                geo, stacks, row(lights.sun_toward, light), math.inf,
                row(lights.sun_intensity, light), origin, n, to_viewer, kd, ks, shininess,
            ),
        )  # fmt: skip
    for light in range(lights.point_position.shape[0]):
        colour = add(
            colour,
            light_from(
                geo,
                stacks,
                row(lights.point_position, light),
                row(lights.point_intensity, light),
                row(lights.point_attenuation, light),
                origin,
                n,
                to_viewer,
                kd,
                ks,
                shininess,
            ),
        )
    samples = frame.options[OPTION_SHADOW_SAMPLES]
    pattern = frame.options[OPTION_SHADOW_PATTERN]
    for light in range(lights.area_centre.shape[0]):
        centre = row(lights.area_centre, light)
        edge_u, edge_v = row(lights.area_edge_u, light), row(lights.area_edge_v, light)
        intensity = row(lights.area_intensity, light)
        attenuation = row(lights.area_attenuation, light)
        total = (0.0, 0.0, 0.0)
        shift_a = shift_b = 0.0
        if pattern == SHADOW_HALTON:
            shift_a, shift_b = uniform2(key, PURPOSE_LIGHT_SHIFT, event * 65536 + light, 0)
        for j in range(samples):
            if pattern == SHADOW_HALTON:
                a = (radical_inverse(j + 1, 2) + shift_a) % 1.0
                b = (radical_inverse(j + 1, 3) + shift_b) % 1.0
            else:
                a, b = uniform2(key, PURPOSE_LIGHT, event * 65536 + light, j)
            if pattern == SHADOW_STRATIFIED:
                x0, y0, w, h = stratified_cell(j, samples)
                a, b = x0 + a * w, y0 + b * h
            position = add(centre, add(scale(edge_u, a - 0.5), scale(edge_v, b - 0.5)))
            total = add(
                total,
                light_from(
                    geo,
                    stacks,
                    position,
                    intensity,
                    attenuation,
                    origin,
                    n,
                    to_viewer,
                    kd,
                    ks,
                    shininess,
                ),
            )
        colour = add(colour, scale(total, 1.0 / samples))
    return colour
