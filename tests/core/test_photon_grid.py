"""The photon pass's bookkeeping (core.compile.photon_grid, core.compile.caustics.shares),
against the plain way of doing the same:

- the disks' radii, found visiting the photons along a Morton curve and skipping the passes
  where no photon can settle, are bit for bit those of passes over the photons in the order
  they were traced, every pass run (the way before: an exact acceleration, so the pictures
  are unchanged);
- the Morton order puts photons near in space near in the order;
- the photons a budget sets are shared among the rows (light, hull) to the photon;
- traced on 1, 2 or 5 threads, the photons are the same, in the same order.
"""

import math

import numpy as np

from core.compile.photon_grid import (
    REACH,
    SPACING_SHARE,
    cell_counts,
    hashed_grid,
    may_settle,
    neighbour_distances,
    neighbours_wanted,
    spatial_order,
)
from core.compile.photon_tracer import shares
from core.kernels.caustics import neighbour_radii


def _radii_every_pass_in_traced_order(position):
    """The rule of neighbour_distances, run plainly: each pass over every unsettled photon
    in the given order, on the full hashed grid (hashed_grid, as the gather's)."""
    m = len(position)
    extent = float(np.linalg.norm(position.max(axis=0) - position.min(axis=0)))
    cap = max(REACH * extent, 1e-9)
    radius, todo = np.full(m, cap), np.ones(m, bool)
    wanted = neighbours_wanted(m)
    edge = max(extent / math.sqrt(m) / SPACING_SHARE, 1e-9)
    while todo.any() and edge < cap:
        _, cells = hashed_grid(position, np.full(m, edge), np.array([edge]))
        neighbour_radii(position, cells, edge, len(cells) - 2, wanted, radius, todo)
        edge *= 2.0
    return np.minimum(radius, cap)


def _caustic_like(count, seed):
    """Photons on a floor: a broad pool, a bright focus a thousandth its size, a few strays
    off the floor (a caustic on a wall)."""
    rng = np.random.default_rng(seed)
    pool = rng.normal(0.0, 1.0, (count // 2, 3)) * (1.0, 1.0, 0.0)
    focus = rng.normal(0.0, 1e-3, (count // 2 - 100, 3)) * (1.0, 1.0, 0.0) + (0.5, 0.2, 0.0)
    wall = rng.uniform(-2.0, 2.0, (100, 3)) * (0.0, 1.0, 1.0) + (3.0, 0.0, 0.0)
    return rng.permutation(np.vstack([pool, focus, wall]))


def test_the_radii_are_those_of_every_pass_in_traced_order_bit_for_bit():
    # and photons filling a box evenly (a caustic over a rough, folded surface): settled in
    # the pass where 27 cells first hold k between them, each cell holding near k / 27
    box = np.random.default_rng(5).uniform(0.0, 1.0, (30_000, 3))
    clouds = [_caustic_like(count, seed) for count, seed in ((60_000, 1), (5_000, 2), (400, 3))]
    for position in [*clouds, box]:
        np.testing.assert_array_equal(neighbour_distances(position),
                                      _radii_every_pass_in_traced_order(position))  # fmt: skip


def test_a_pass_is_skipped_only_where_no_photon_can_settle():
    """Photons on a lattice, two a cell edge each way: every cell holds 8, so the 27 about
    an inner photon hold 216, enough for k = 207 of 35^3 photons, though no 9 cells do;
    at half the edge (one a cell) none settles, and the pass may be skipped."""
    axis = (np.arange(35) + 0.25) * 1.0
    lattice = np.stack(np.meshgrid(axis, axis, axis, indexing="ij"), -1).reshape(-1, 3)
    wanted = neighbours_wanted(len(lattice))
    for edge, settles in ((2.0, True), (1.0, False)):
        cells = cell_counts(lattice, edge)
        todo = np.ones(len(lattice), bool)
        neighbour_radii(lattice, cells, edge, len(cells) - 2, wanted, np.zeros(len(lattice)),
                        todo)  # fmt: skip
        assert (not todo.all()) == settles == may_settle(cells, wanted), edge


def test_the_morton_order_keeps_neighbours_together():
    rng = np.random.default_rng(4)
    position = rng.uniform(0.0, 1.0, (20_000, 3))
    order = spatial_order(position)
    assert sorted(order.tolist()) == list(range(len(position)))
    steps = np.linalg.norm(np.diff(position[order], axis=0), axis=1)
    shuffled = np.linalg.norm(np.diff(position, axis=0), axis=1)
    # the curve's median step is about the photons' spacing (20,000^(-1/3) = 0.037), a
    # random order's about half the box
    assert np.median(steps) < 0.05 < 0.5 * np.median(shuffled)


def test_a_budget_is_shared_among_the_rows_to_the_photon():
    power = np.array([0.3, 0.3, 0.4, 1e-9, 0.0, 2.7])
    for count in (1_600_000, 8192, 25_000, 7):
        share = shares(count, power)
        assert share.sum() == count and share[4] == 0
        assert np.all(np.abs(share - count * power / power.sum()) < 1.0)


def test_the_photons_are_the_same_on_any_number_of_threads():
    from core import RenderSettings
    from core.compile import compile_scene
    from tests.benchmarks.bench_caustics import ball_lens_scene

    def lights(threads):
        settings = RenderSettings(32, 32, pixel_samples=1, glass_shadows="blocked",
                                  caustics=("reflective", "refractive"), caustic_photons=60_000,
                                  max_depth=12, threads=threads)  # fmt: skip
        compiled = compile_scene(ball_lens_scene(), settings)
        assert compiled.caustics.traced == 60_000  # in some 30 parts
        return compiled.packed.lights

    one = lights(1)
    for threads in (2, 5):
        other = lights(threads)
        for name in ("photon_position", "photon_direction", "photon_power", "photon_radius"):
            np.testing.assert_array_equal(getattr(one, name), getattr(other, name))
