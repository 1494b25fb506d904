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
    (core.kernels.caustics.neighbour_radii).

    The passes visit the photons in space-filling-curve order (`spatial_order`): each
    photon's radius depends on the cells' counts alone, so the order changes no radius,
    but neighbours then read the same buckets one after another, from the cache (at a
    million photons a pass in the order they were traced missed it at nearly every one of
    its 27 look-ups, and took most of the photon pass's time)."""
    m = len(position)
    extent = float(np.linalg.norm(position.max(axis=0) - position.min(axis=0)))
    cap = max(REACH * extent, 1e-9)
    radius = np.full(m, cap)
    wanted = neighbours_wanted(m)
    if wanted < 1:
        return radius
    order = spatial_order(position)
    ordered = np.ascontiguousarray(position[order])
    found = np.full(m, cap)
    todo = np.ones(m, bool)
    # from cells finer than the photons' mean spacing (were they all on one square), so
    # that crowded photons are settled on cells their size
    edge = max(extent / math.sqrt(m) / SPACING_SHARE, 1e-9)
    while todo.any() and edge < cap:
        cells = cell_counts(ordered, edge)
        if may_settle(cells, wanted):
            neighbour_radii(ordered, cells, edge, len(cells) - 2, wanted, found, todo)
        edge *= 2.0
    radius[order] = found
    return np.minimum(radius, cap)


def may_settle(cells: np.ndarray, wanted: int) -> bool:
    """Whether a pass on `cells` can settle any photon: one settles where its 27 buckets
    hold itself and `wanted` more, never while 27 of the fullest fall short (the finest
    passes, at a million photons)."""
    return 27 * int(np.diff(cells).max()) > wanted


def spatial_order(position: np.ndarray) -> np.ndarray:
    """The photons' order along a Morton (Z-order) curve through their box, 21 bits an
    axis: photons near each other in space come near each other in the order."""
    low = position.min(axis=0)
    span = max(float((position.max(axis=0) - low).max()), 1e-30)
    grid = ((position - low) * ((2**21 - 1) / span)).astype(np.uint64)
    key = np.zeros(len(position), np.uint64)
    for axis in range(3):
        key |= _spread_bits(grid[:, axis]) << np.uint64(axis)
    return np.argsort(key)  # ties in any order: no radius depends on it


def _spread_bits(v: np.ndarray) -> np.ndarray:
    """21-bit integers with two zero bits put after each bit (Morton's interleaving)."""
    v = v & np.uint64(0x1FFFFF)
    for shift, mask in ((32, 0x1F00000000FFFF), (16, 0x1F0000FF0000FF), (8, 0x100F00F00F00F00F),
                        (4, 0x10C30C30C30C30C3), (2, 0x1249249249249249)):  # fmt: skip
        v = (v | (v << np.uint64(shift))) & np.uint64(mask)
    return v


def cell_counts(position: np.ndarray, edge: float) -> np.ndarray:
    """Lights.photon_cells of the photons in cells of `edge` (hashed as one level): the
    bucket starts, without the photons' order, which the radius passes do not read."""
    buckets = _bucket_count(len(position))
    bucket = np.empty(len(position), np.int64)
    photon_buckets(position, np.full(len(position), edge), np.array([edge]), buckets - 1, bucket)
    return _bucket_starts(bucket, buckets)


def _bucket_count(photons: int) -> int:
    return 1 << max(4, int(2 * photons - 1).bit_length())


def radius_levels(radius: np.ndarray) -> np.ndarray:
    """The levels' cell edges: the smallest radius, doubling up to the largest."""
    low, high = float(radius.min()), float(radius.max())
    count = min(MAX_LEVELS, int(math.ceil(math.log2(high / low))) + 1 if high > low else 1)
    levels = low * 2.0 ** np.arange(count)
    levels[-1] = max(levels[-1], high)
    return levels


def hashed_grid(position: np.ndarray, radius: np.ndarray, levels: np.ndarray):
    """(the photons' order by bucket, Lights.photon_cells) for the levels' grids."""
    buckets = _bucket_count(len(position))
    bucket = np.empty(len(position), np.int64)
    photon_buckets(position, radius, levels, buckets - 1, bucket)
    return np.argsort(bucket, kind="stable"), _bucket_starts(bucket, buckets)


def _bucket_starts(bucket: np.ndarray, buckets: int) -> np.ndarray:
    """Lights.photon_cells: where each bucket's photons start, once ordered by bucket."""
    cells = np.zeros(buckets + 1, np.int64)
    np.cumsum(np.bincount(bucket, minlength=buckets), out=cells[1:])
    return cells
