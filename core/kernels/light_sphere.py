"""Point and spot lights with a radius: a sphere, or a disk turned towards the lit point.

A light of power P has radiant intensity I = P / (4 pi) and, with radius r, radiance
I / (pi r^2) on its surface, so that far away both shapes give the point light's I / d^2.
Each sample returns (unit direction to the light, distance to its surface, weight) with

    weight = (light arriving from that direction / the density it was picked with) / (I pi)

so that the emitter table's radiance, I / pi (`core.kernels.emitters`), times the weight and
N.L averages to E / pi, the brightness a white Lambertian surface has in Cycles.

- Sphere seen from outside: directions uniform in the cone it fills, half-angle theta_max
  with sin theta_max = r / d; weight 2 / (d^2 (1 + cos theta_max)), 1 / d^2 for r = 0.
- Sphere seen from inside: light from every direction; cosine-weighted about the normal,
  weight 1 / (r^2 cos).
- Disk facing the point (Soft Falloff): uniform on the disk; weight cos_l / t^2, cos_l
  between the disk's normal (towards the point) and the ray.

A spot light is either shape masked by a cone: Blender's smoothstep over the blend, and
before Blender 4.0 also the cosine from the axis.
"""

import math

from ..jit.decorators import inlined_kernel, kernel
from .light_samples import concentric_disk, cone_direction, in_frame
from .vec import add, dot, normalize, scale, sub


@kernel
def sphere_sample(centre, radius, origin, normal, a, b):
    """(direction, distance, weight) of the sphere's sample (a, b), seen from `origin`."""
    to_centre = sub(centre, origin)
    d2 = dot(to_centre, to_centre)
    d = math.sqrt(d2)
    r2 = radius * radius
    if d2 > r2:
        w = scale(to_centre, 1.0 / d)
        sin2_max = r2 / d2
        cos_max = math.sqrt(max(0.0, 1.0 - sin2_max))
        direction = cone_direction(w, sin2_max / (1.0 + cos_max), a, b)
        # The nearer crossing of the ray and the sphere (law of cosines)
        along = dot(direction, to_centre)
        t = along - math.sqrt(max(0.0, r2 - (d2 - along * along)))
        return direction, max(t, 0.0), 2.0 / (d2 * (1.0 + cos_max))
    # Inside the light: it shines from all round; the half towards the normal matters
    phi = 2.0 * math.pi * b
    s = math.sqrt(a)
    cos_n = math.sqrt(max(0.0, 1.0 - a))
    if cos_n <= 0.0:
        return normal, 0.0, 0.0
    direction = in_frame(normal, s * math.cos(phi), s * math.sin(phi), cos_n)
    # Out through the sphere's surface: the far crossing, as the ray starts inside it
    along = dot(direction, to_centre)
    t = along + math.sqrt(max(0.0, r2 - (d2 - along * along)))
    return direction, t, 1.0 / (r2 * cos_n)


@kernel
def facing_disk_sample(centre, radius, origin, a, b):
    """(direction, distance, weight) of sample (a, b) of the disk of `radius` at `centre`
    turned towards `origin`."""
    away = sub(origin, centre)
    d = math.sqrt(dot(away, away))
    if d == 0.0:
        return (0.0, 0.0, 1.0), 0.0, 0.0
    facing = scale(away, 1.0 / d)
    x, y = concentric_disk(a, b)
    point = add(centre, in_frame(facing, radius * x, radius * y, 0.0))
    to_point = sub(point, origin)
    t = math.sqrt(dot(to_point, to_point))
    if t == 0.0:
        return facing, 0.0, 0.0
    direction = scale(to_point, 1.0 / t)
    cos_light = -dot(facing, direction)
    return direction, t, max(cos_light, 0.0) / (t * t)


@inlined_kernel
def spot_mask(to_light_frame, from_light, cos_half, blend_width, with_cosine):
    """How much of a spot light's light leaves along unit `from_light` (world): 0 outside
    its cone, 1 inside the blend, Blender's smoothstep across it. `to_light_frame` holds the
    three rows taking world directions into the light's frame, whose -Z is the axis."""
    row_x, row_y, row_z = to_light_frame
    local = normalize((dot(row_x, from_light), dot(row_y, from_light), dot(row_z, from_light)))
    along = -local[2]
    if along <= cos_half:
        return 0.0
    if blend_width > 0.0:
        x = min((along - cos_half) / blend_width, 1.0)
        mask = x * x * (3.0 - 2.0 * x)
    else:
        mask = 1.0
    return mask * along if with_cosine else mask
