"""Where the stored photons' disks reach: each photon's radius, holding about k of its
fellows (NEIGHBOURS), and the hashed grid of levels the gather reads (core.kernels.caustics).
The automatic budget (core.compile.photon_budget) measures the pilot's disks on the screen
with the same radii."""

from __future__ import annotations

import math

import numpy as np

from ..kernels.caustics import neighbour_radii, photon_buckets

# A photon's disk holds about k of its fellows, k = sqrt(m) for m stored photons within
# these bounds: the estimate's noise falls as 1 / sqrt(k) and its blur grows as sqrt(k / m),
# so both fall as m^(-1/4)
NEIGHBOURS = (32, 1024)
REACH = 0.125  # a lone photon's disk: this share of the photons' extent
MAX_LEVELS = 24
SPACING_SHARE = 64


def neighbours_wanted(stored: int) -> int:
    """k: the fellows a photon's disk holds among `stored` photons (NEIGHBOURS' rule)."""
    return min(int(np.clip(math.sqrt(stored), *NEIGHBOURS)), stored - 1)


def neighbour_distances(position: np.ndarray) -> np.ndarray:
    """Each photon's disk radius: one that holds about k of its fellows (NEIGHBOURS) at
    their density about it, at most REACH of the photons' extent (a lone photon's disk):
    found in passes of doubling cells, each pass settling the photons whose 27 cells hold k
    (core.kernels.caustics.neighbour_radii)."""
    m = len(position)
    extent = float(np.linalg.norm(position.max(axis=0) - position.min(axis=0)))
    cap = max(REACH * extent, 1e-9)
    radius = np.full(m, cap)
    todo = np.ones(m, bool)
    wanted = neighbours_wanted(m)
    if wanted < 1:
        return radius
    # from cells finer than the photons' mean spacing (were they all on one square), so
    # that crowded photons are settled on cells their size
    edge = max(extent / math.sqrt(m) / SPACING_SHARE, 1e-9)
    while todo.any() and edge < cap:
        levels = np.array([edge])
        _, cells = hashed_grid(position, np.full(m, edge), levels)
        neighbour_radii(position, cells, edge, len(cells) - 2, wanted, radius, todo)
        edge *= 2.0
    return np.minimum(radius, cap)


def radius_levels(radius: np.ndarray) -> np.ndarray:
    """The levels' cell edges: the smallest radius, doubling up to the largest."""
    low, high = float(radius.min()), float(radius.max())
    count = min(MAX_LEVELS, int(math.ceil(math.log2(high / low))) + 1 if high > low else 1)
    levels = low * 2.0 ** np.arange(count)
    levels[-1] = max(levels[-1], high)
    return levels


def hashed_grid(position: np.ndarray, radius: np.ndarray, levels: np.ndarray):
    """(the photons' order by bucket, Lights.photon_cells) for the levels' grids."""
    buckets = 1 << max(4, int(2 * len(position) - 1).bit_length())
    bucket = np.empty(len(position), np.int64)
    photon_buckets(position, radius, levels, buckets - 1, bucket)
    order = np.argsort(bucket, kind="stable")
    counts = np.bincount(bucket, minlength=buckets)
    cells = np.zeros(buckets + 1, np.int64)
    np.cumsum(counts, out=cells[1:])
    return order, cells
