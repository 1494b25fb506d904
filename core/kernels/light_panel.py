"""Area lights: a rectangle or an ellipse, shining from one side as a Lambertian emitter.

A panel of power P and area A has radiance L = P / (pi A). Samples are uniform over its
area (the unit square's point as it is on a rectangle, through the concentric map on an
ellipse), each returning (unit direction, distance, weight) with

    weight = cos_l / t^2,  cos_l = N_light . (-direction), 0 behind the panel

so that the emitter table's radiance, P / pi^2 = L A / pi (`core.kernels.emitters`), times the
weight and N.L averages to E / pi, the brightness a white Lambertian surface has in Cycles.
"""

import math

from ..jit.decorators import kernel
from .light_samples import concentric_disk
from .vec import add, dot, scale, sub


@kernel
def panel_sample(centre, edge_u, edge_v, normal, ellipse, origin, a, b):
    """(direction, distance, weight) of the panel's sample (a, b) seen from `origin`;
    `normal` is the unit direction it shines towards."""
    if ellipse:
        x, y = concentric_disk(a, b)
        s, t_ = 0.5 * x, 0.5 * y
    else:
        s, t_ = a - 0.5, b - 0.5
    point = add(centre, add(scale(edge_u, s), scale(edge_v, t_)))
    to_point = sub(point, origin)
    t = math.sqrt(dot(to_point, to_point))
    if t == 0.0:
        return normal, 0.0, 0.0
    direction = scale(to_point, 1.0 / t)
    cos_light = -dot(normal, direction)
    if cos_light <= 0.0:
        return direction, 0.0, 0.0
    return direction, t, cos_light / (t * t)
