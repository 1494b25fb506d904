"""The caustic light at a shading point: a density estimate over the photons stored near it
(core.kernels.photons).

Each photon i spreads its power P_i over a disk of its own radius r_i about where it landed,
wide enough to hold about k of its fellows at their density there (core.compile.caustics):
small where photons crowd (a focus stays sharp), wide where they are few (a faint glow stays
smooth).
The irradiance at a point is

    E = sum over photons i with d_i < r_i of  P_i K(d_i, r_i),
    K(d, r) = 2 / (pi r^2) (1 - d^2 / r^2)

Epanechnikov's kernel on the disk: it integrates to 1 over the disk, so each photon's power
is kept whole (Silverman's "variable kernel" estimate). Only photons that arrived at the side
the point faces count, and only those within a quarter of their radius of its tangent plane,
so that light on one face of a thin wall, or round a corner, is not spread to the other. A
Lambertian surface of colour kd shows kd E / pi (core.kernels.emitters' units).

Finding them: photons are grouped in levels by radius, level l holding radii in
(c_l / 2, c_l] with c_l = Lights.photon_levels[l] (level 0 every radius up to c_0), and each
level in a grid of cells of edge c_l, hashed into one table (Lights.photon_cells): the 27
cells about the point's own, per level, hold every photon whose disk can reach it.
"""

import math

import numpy as np

from ..jit.decorators import kernel
from .vec import dot, sub

# Photons count only within this share of their radius from the point's tangent plane
PLANE_SHARE = 0.25
# The hash of a grid cell: coordinates and level times large primes, mixed by xor
_PX, _PY, _PZ, _PL = 73856093, 19349663, 83492791, 2654435761


@kernel
def cell_hash(ix, iy, iz, level, mask):
    """The bucket of grid cell (ix, iy, iz) of `level` in a table of mask + 1 buckets."""
    return ((ix * _PX) ^ (iy * _PY) ^ (iz * _PZ) ^ (level * _PL)) & mask


@kernel
def _cell(x, edge):
    return np.int64(math.floor(x / edge))


@kernel
def photon_level(radius, levels):
    """The level whose band holds `radius` (the module's rule)."""
    for level in range(levels.shape[0]):
        if radius <= levels[level]:
            return level
    return levels.shape[0] - 1


@kernel
def photon_buckets(position, radius, levels, mask, out):
    """Each photon's bucket into `out` (the compile orders them by it)."""
    for i in range(position.shape[0]):
        level = photon_level(radius[i], levels)
        edge = levels[level]
        out[i] = cell_hash(_cell(position[i, 0], edge), _cell(position[i, 1], edge),
                           _cell(position[i, 2], edge), np.int64(level), mask)  # fmt: skip


@kernel
def caustic_irradiance(lights, p, n):
    """(R, G, B) irradiance by caustic photons at point p of a surface whose unit normal n
    faces the viewer (the module's estimate); zero without photons."""
    cells = lights.photon_cells
    if cells.shape[0] == 0:
        return 0.0, 0.0, 0.0
    levels = lights.photon_levels
    mask = np.int64(cells.shape[0] - 2)
    position, direction = lights.photon_position, lights.photon_direction
    power, radius = lights.photon_power, lights.photon_radius
    e0 = e1 = e2 = 0.0
    for level in range(levels.shape[0]):
        edge = levels[level]
        low = levels[level - 1] if level > 0 else 0.0
        ix, iy, iz = _cell(p[0], edge), _cell(p[1], edge), _cell(p[2], edge)
        for dx in range(-1, 2):
            for dy in range(-1, 2):
                for dz in range(-1, 2):
                    cx, cy, cz = ix + dx, iy + dy, iz + dz
                    bucket = cell_hash(cx, cy, cz, np.int64(level), mask)
                    for i in range(cells[bucket], cells[bucket + 1]):
                        r = radius[i]
                        if r <= low or r > edge:
                            continue  # another level's, in the same bucket
                        q = (position[i, 0], position[i, 1], position[i, 2])
                        if (
                            _cell(q[0], edge) != cx
                            or _cell(q[1], edge) != cy
                            or _cell(q[2], edge) != cz
                        ):
                            continue  # another cell's, in the same bucket
                        gap = sub(q, p)
                        d2 = dot(gap, gap)
                        r2 = r * r
                        if d2 >= r2 or abs(dot(gap, n)) > PLANE_SHARE * r:
                            continue
                        arriving = (direction[i, 0], direction[i, 1], direction[i, 2])
                        if dot(arriving, n) >= 0.0:
                            continue  # it arrived at the other face
                        k = 2.0 / (math.pi * r2) * (1.0 - d2 / r2)
                        e0 += power[i, 0] * k
                        e1 += power[i, 1] * k
                        e2 += power[i, 2] * k
    return e0, e1, e2


@kernel
def neighbour_radii(position, cells, edge, mask, wanted, out, todo):
    """For each photon i with todo[i]: if the 3 x 3 x 3 cells of `edge` about it (hashed as
    level 0 into `cells`) hold at least `wanted` others, the radius of a disk that holds
    about `wanted` photons at their density there (as if on a plane across the nine cells
    about it: count / 9 edge^2) into out[i], and todo[i] cleared; otherwise left to a pass
    of larger cells. Counting bucket sizes, not distances: each pass costs 27 look-ups a
    photon, whatever the crowd (an exact k-th neighbour search cost minutes for a million
    photons at k = 1000)."""
    for i in range(position.shape[0]):
        if not todo[i]:
            continue
        ix, iy, iz = (
            _cell(position[i, 0], edge),
            _cell(position[i, 1], edge),
            _cell(position[i, 2], edge),
        )
        listed = -1  # itself
        for dx in range(-1, 2):
            for dy in range(-1, 2):
                for dz in range(-1, 2):
                    bucket = cell_hash(ix + dx, iy + dy, iz + dz, np.int64(0), mask)
                    listed += cells[bucket + 1] - cells[bucket]
        if listed < wanted:
            continue
        out[i] = edge * math.sqrt(9.0 * wanted / (math.pi * listed))
        todo[i] = False
