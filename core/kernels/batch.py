"""Many rays at once, for benchmarks, tests and tools: nearest hits, the surface normals
there, and shadow queries.

Each entry point loops over the rays inside one GIL-free kernel, so callers can split a batch
across threads themselves; one `Stacks` (from a `Workspace`) per calling thread. They take
the packed scene's `geometry` group (and its `surfaces` group for normals).
"""

from ..jit.decorators import kernel
from .light_pyramid import TRAVERSE_ALL
from .surface import surface_at
from .trace import closest_hit, transmittance


@kernel
def closest_hits(geo, origins, directions, t_max, out_t, out_shape, out_part, stacks):
    """Nearest hit of each ray: out_t (NO_HIT on a miss), out_shape (-1), out_part."""
    for i in range(origins.shape[0]):
        o = (origins[i, 0], origins[i, 1], origins[i, 2])
        d = (directions[i, 0], directions[i, 1], directions[i, 2])
        shape, t, part, _, _ = closest_hit(geo, o, d, t_max, stacks)
        out_t[i] = t
        out_shape[i] = shape
        out_part[i] = part


@kernel
def closest_normals(geo, surf, origins, directions, t_max, out_t, out_shape, out_normal, stacks):
    """`closest_hits` with the shading normal at each hit (unit, outward; zero on a miss):
    what the renderer shades with, interpolated across smooth mesh faces."""
    for i in range(origins.shape[0]):
        o = (origins[i, 0], origins[i, 1], origins[i, 2])
        d = (directions[i, 0], directions[i, 1], directions[i, 2])
        shape, t, part, b1, b2 = closest_hit(geo, o, d, t_max, stacks)
        out_t[i] = t
        out_shape[i] = shape
        n = (0.0, 0.0, 0.0)
        if shape >= 0:
            n = surface_at(geo, surf, shape, part, b1, b2, o, d, t, False)[2]
        out_normal[i, 0] = n[0]
        out_normal[i, 1] = n[1]
        out_normal[i, 2] = n[2]


@kernel
def shadow_rays(geo, origins, directions, t_max, out_light, stacks):
    """Transmittance of each segment origin + t direction, 0 < t < t_max[i], by the
    constant shares: a surface whose share varies over it (`core.kernels.shadow_log`)
    counts 1 here; `core.kernels.shadow_crossing.light_along` answers it too."""
    for i in range(origins.shape[0]):
        o = (origins[i, 0], origins[i, 1], origins[i, 2])
        d = (directions[i, 0], directions[i, 1], directions[i, 2])
        out_light[i] = transmittance(geo, o, d, t_max[i], stacks, TRAVERSE_ALL)
