"""The environment (Blender's World) at the kernels: what a ray that leaves the scene sees, and
the light it gives a diffuse surface.

Seen: the background colour when there is no environment; the uniform colour; or the
equirectangular image (`core.model.environment`), looked up along the ray's direction taken
through the Mapping rows, times its tint.

Light: N = OPTION_ENVIRONMENT_SAMPLES shadow rays per shading point, each towards a direction
w_j picked with density p(w_j), unoccluded ones adding

    kd (N.w_j) L(w_j) / (pi p(w_j)) / N

(its mean is kd E / pi, E the irradiance, as in Cycles). Directions are cosine-weighted about
the normal, p = (N.w) / pi, for a uniform colour (each ray then adds exactly kd L / N: a white
world gives a white unshadowed surface its albedo, the furnace test) and for an image whose
Mapping is more than a rotation; otherwise an image's pixels are picked in proportion to
their light (`core.compile.environment`), p(w) = p_pixel w h / (2 pi^2 sin theta), so a small
bright sun is found by most rays. Only diffuse light is gathered: highlights come from lights.
"""

import math

from ..jit.decorators import kernel
from .bent_normal import terminator_term
from .layout import ENVIRONMENT_IMAGE, ENVIRONMENT_NONE, ENVIRONMENT_UNIFORM
from .light_pyramid import TRAVERSE_ALL
from .light_samples import in_frame, light_spread, square_point
from .options import (
    HIDDEN_FROM_CAMERA,
    HIDDEN_FROM_DIFFUSE,
    HIDDEN_FROM_GLOSSY,
    HIDDEN_FROM_TRANSMISSION,
    OPTION_ENVIRONMENT,
    OPTION_ENVIRONMENT_CLOSEST,
    OPTION_ENVIRONMENT_HIDDEN,
    OPTION_ENVIRONMENT_SAMPLES,
    OPTION_ROUGH_DIFFUSE,
    OPTION_SHADOW_PATTERN,
    SHADOW_HALTON,
)
from .rng import PURPOSE_LIGHT_SHIFT, uniform2
from .rough_diffuse import beyond_kd, rough_response
from .shading import add_falling, seen_through
from .shadow_rays import shadow_visibility
from .surface import bilinear, nearest
from .vec import add, affine, as_tuple, dot, mul, row, scale

# The environment's random stream at each shading event, apart from every light's
ENVIRONMENT_STREAM = 65535


@kernel
def equirectangular_uv(m):
    """Blender's equirectangular (u, v) of direction m, any length; (0, 0) for zero."""
    length = math.sqrt(dot(m, m))
    if length == 0.0:
        return 0.0, 0.0
    u = (math.pi - math.atan2(m[1], m[0])) / (2.0 * math.pi)
    v = 1.0 - math.acos(min(1.0, max(-1.0, m[2] / length))) / math.pi
    return u, v


@kernel
def environment_seen(frame, lights, d, depth, came_through):
    """What a ray leaving the scene along d sees: a camera ray (depth 0), a refracted one
    (`came_through`) or a reflected one; black to those the World's Ray Visibility hides it
    from."""
    hidden = frame.options[OPTION_ENVIRONMENT_HIDDEN]
    if depth == 0:
        bit = HIDDEN_FROM_CAMERA
    else:
        bit = HIDDEN_FROM_TRANSMISSION if came_through else HIDDEN_FROM_GLOSSY
    if hidden & bit:
        return (0.0, 0.0, 0.0)
    return environment_radiance(frame, lights, d)


@kernel
def environment_radiance(frame, lights, d):
    """What a ray leaving the scene along d sees (linear RGB radiance)."""
    kind = frame.options[OPTION_ENVIRONMENT]
    if kind == ENVIRONMENT_NONE:
        return as_tuple(frame.background)
    tint = as_tuple(lights.env_colour)
    if kind == ENVIRONMENT_UNIFORM:
        return tint
    u, v = equirectangular_uv(affine(lights.env_transform, d))
    width, height = lights.env_size[0], lights.env_size[1]
    if frame.options[OPTION_ENVIRONMENT_CLOSEST]:
        return mul(tint, nearest(lights.env_pixels, 0, width, height, u, v))
    return mul(tint, bilinear(lights.env_pixels, 0, width, height, u, v))


@kernel
def _interval(cdf, x):
    """i with cdf[i] <= x < cdf[i + 1] (cdf rising from 0 to 1), and x's place in it."""
    low, high = 0, cdf.shape[0] - 1
    while high - low > 1:
        middle = (low + high) // 2
        if cdf[middle] <= x:
            low = middle
        else:
            high = middle
    width = cdf[low + 1] - cdf[low]
    offset = (x - cdf[low]) / width if width > 0.0 else 0.5
    return low, min(max(offset, 0.0), 1.0), width


@kernel
def sample_image(lights, a, b):
    """(world direction, its density per solid angle) of a direction picked from the image by
    its light, for the unit square's point (a, b). The Mapping must be a rotation."""
    width, height = lights.env_size[0], lights.env_size[1]
    i, fi, row_share = _interval(lights.env_row_cdf, a)
    j, fj, pixel_share = _interval(lights.env_column_cdf[i], b)
    theta = math.pi * (i + fi) / height
    phi = math.pi - 2.0 * math.pi * (j + fj) / width
    sin_theta = math.sin(theta)
    if sin_theta <= 0.0:
        return (0.0, 0.0, 1.0), 0.0
    m = (sin_theta * math.cos(phi), sin_theta * math.sin(phi), math.cos(theta))
    # The rotation's transpose takes the lookup direction back to the world's
    t = lights.env_transform
    d = (
        t[0, 0] * m[0] + t[1, 0] * m[1] + t[2, 0] * m[2],
        t[0, 1] * m[0] + t[1, 1] * m[1] + t[2, 1] * m[2],
        t[0, 2] * m[0] + t[1, 2] * m[1] + t[2, 2] * m[2],
    )
    density = row_share * pixel_share * width * height / (2.0 * math.pi * math.pi * sin_theta)
    return d, density


@kernel
def environment_light(frame, lights, geo, stacks, point, kd, rough, key, event, split):
    """The environment's diffuse light at a `ShadingPoint` of a surface of diffuse colour
    kd (the module's formula), Oren-Nayar's of roughness `rough` where it is above 0
    (core.kernels.rough_diffuse, each direction's stand-in for kd). With `split`,
    stacks.terms gets the light falling too."""
    kind = frame.options[OPTION_ENVIRONMENT]
    samples = frame.options[OPTION_ENVIRONMENT_SAMPLES]
    if kind == ENVIRONMENT_NONE or samples == 0:
        return (0.0, 0.0, 0.0)
    if frame.options[OPTION_ENVIRONMENT_HIDDEN] & HIDDEN_FROM_DIFFUSE:
        return (0.0, 0.0, 0.0)
    targets, visibility, terms = stacks.light_targets, stacks.visibility, stacks.terms
    n = point.normal
    pattern = frame.options[OPTION_SHADOW_PATTERN]
    stream = event * 65536 + ENVIRONMENT_STREAM
    shift = (0.0, 0.0)
    if pattern == SHADOW_HALTON:
        shift = uniform2(key, PURPOSE_LIGHT_SHIFT, stream, 0)
    spread = light_spread(stacks.light_strata, pattern, samples, stream)
    by_image = kind == ENVIRONMENT_IMAGE and lights.env_size[2] == 1
    for j in range(samples):
        a, b = square_point(pattern, samples, j, key, stream, shift, spread)
        if by_image:
            d, density = sample_image(lights, a, b)
        else:
            # Cosine-weighted about the normal
            radius, phi = math.sqrt(a), 2.0 * math.pi * b
            cos_n = math.sqrt(max(0.0, 1.0 - a))
            d = in_frame(n, radius * math.cos(phi), radius * math.sin(phi), cos_n)
            density = cos_n / math.pi
        targets[j, 0], targets[j, 1], targets[j, 2] = d
        usable = density > 0.0 and dot(n, d) > 0.0
        targets[j, 3] = math.inf if usable else 0.0
        targets[j, 4] = 1.0 / (math.pi * density) if usable else 0.0
    shadow_visibility(geo, stacks, TRAVERSE_ALL, point.origin, n, 0, samples)
    total = (0.0, 0.0, 0.0)
    for j in range(samples):
        if targets[j, 3] == 0.0 or visibility[j] == 0.0:
            continue
        d = row(targets, j)
        radiance = scale(environment_radiance(frame, lights, d), targets[j, 4] / samples)
        seen = seen_through(stacks, j)
        term = terminator_term(point.smooth_normal, n, d, point.terminator)
        cos = dot(n, d) * term
        reflectance = kd
        if rough > 0.0:
            model = frame.options[OPTION_ROUGH_DIFFUSE]
            reflectance = rough_response(kd, rough, model, n, d, point.to_viewer)
        total = add(total, mul(reflectance, mul(radiance, scale(seen, cos))))
        if split:
            add_falling(terms, d, radiance, seen, n, beyond_kd(kd, reflectance, term))
    return total
