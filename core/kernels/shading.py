"""The report's lighting model: ambient + per light diffuse and Phong specular, hard shadows.

    colour = kd * ambient
           + sum over lights of (kd (N.L) + ks (R.V)^p) * I / (c0 + c1 d + c2 d^2)

where a light contributes only if N.L > 0 and nothing lies between the point and the light.
"""

import math

from core.jit import kernel
from core.kernels.trace import occluded, spawn_point
from core.kernels.vec import add, as_tuple, dot, mul, row, scale, sub


@kernel
def shade(ps, shape, p, n, d, ray_origin):
    """Colour seen along unit direction d at point p of `shape` with unit outward normal n."""
    material = ps.shape_material[shape]
    kd = row(ps.material_diffuse, material)
    ks = row(ps.material_specular, material)
    shininess = ps.material_shininess[material]
    has_specular = ks[0] > 0.0 or ks[1] > 0.0 or ks[2] > 0.0

    # Shade the side the ray arrived from: a ray from inside sees the inner face
    if dot(n, d) > 0.0:
        n = scale(n, -1.0)
    to_viewer = scale(d, -1.0)
    origin = spawn_point(p, n, ray_origin)

    colour = mul(kd, as_tuple(ps.ambient))
    for light in range(ps.light_position.shape[0]):
        to_light = sub(row(ps.light_position, light), origin)
        distance = math.sqrt(dot(to_light, to_light))
        if distance == 0.0:
            continue
        light_dir = scale(to_light, 1.0 / distance)
        n_dot_l = dot(n, light_dir)
        if n_dot_l <= 0.0 or occluded(ps, origin, light_dir, distance):
            continue
        c0, c1, c2 = row(ps.light_attenuation, light)
        radiance = scale(
            row(ps.light_intensity, light), 1.0 / (c0 + c1 * distance + c2 * distance**2)
        )
        reflectance = scale(kd, n_dot_l)
        if has_specular:
            # Unit length already: n and light_dir are unit vectors
            reflected = sub(scale(n, 2.0 * n_dot_l), light_dir)
            r_dot_v = dot(reflected, to_viewer)
            if r_dot_v > 0.0:
                reflectance = add(reflectance, scale(ks, r_dot_v**shininess))
        colour = add(colour, mul(reflectance, radiance))
    return colour
