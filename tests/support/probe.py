"""Single rays into a packed scene, for tests: nearest hit, surface, shadow transmittance."""

import math

import numpy as np

from core.compile import pack_scene
from core.kernels.batch import closest_hits
from core.kernels.light_pyramid import TRAVERSE_ALL
from core.kernels.shadow_crossing import light_along
from core.kernels.surface import surface_at
from core.kernels.trace import closest_hit, transmittance
from core.kernels.workspace import new_workspace
from core.model import RenderSettings, Scene

WORKSPACE = new_workspace(8)


def packed_shapes(*shapes, lights=()):
    return pack_scene(
        Scene(shapes=list(shapes), lights=list(lights)), RenderSettings(8, 8, pixel_samples=1)
    )


def hit(packed, origin, direction, t_max=math.inf):
    """(shape, t, part, b1, b2); shape -1 on a miss."""
    o, d = tuple(map(float, origin)), tuple(map(float, direction))
    return closest_hit(packed.geometry, o, d, t_max, WORKSPACE.stacks)


def surface(packed, origin, direction):
    """(shape, t, point, geometric normal, shading normal, (u, v)) or None on a miss."""
    o, d = tuple(map(float, origin)), tuple(map(float, direction))
    shape, t, part, b1, b2 = closest_hit(packed.geometry, o, d, math.inf, WORKSPACE.stacks)
    if shape < 0:
        return None
    p, ng, ns, u, v = surface_at(
        packed.geometry, packed.surfaces, shape, part, b1, b2, o, d, t, True
    )
    return shape, t, np.array(p), np.array(ng), np.array(ns), (u, v)


def light_through(packed, origin, direction, t_max):
    o, d = tuple(map(float, origin)), tuple(map(float, direction))
    return transmittance(packed.geometry, o, d, t_max, WORKSPACE.stacks, TRAVERSE_ALL)


def light_by_full_rule(packed, origin, direction, t_max):
    """`light_through` with the crossings of surfaces whose share varies answered."""
    o, d = tuple(map(float, origin)), tuple(map(float, direction))
    return light_along(packed, WORKSPACE, o, d, t_max)


def hits(packed, origins, directions, t_max=math.inf):
    """Nearest hits of many rays: (t, shape, part) arrays."""
    n = len(origins)
    t, shape, part = np.empty(n), np.empty(n, np.int64), np.empty(n, np.int64)
    closest_hits(
        packed.geometry,
        np.ascontiguousarray(origins, float),
        np.ascontiguousarray(directions, float),
        t_max,
        t,
        shape,
        part,
        WORKSPACE.stacks,
    )
    return t, shape, part
