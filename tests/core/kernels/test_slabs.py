"""The two slab tests (core.kernels.slabs) are conservative, checked against exact rational
arithmetic: they never cull a box that the exact float64 ray or line meets, and the entry
distance they report exceeds the exact one by no more than their slack, which is what
nearest-hit traversal relies on when it skips a waiting box. The rays graze boxes at their
corners, edges and faces from origins of every magnitude, beyond float32's range included,
and the lines (CSG's whole-line queries) also meet boxes that lie behind their origin, where
an exit distance is negative. Also: the slots a leaf block leaves empty are never hit."""

from fractions import Fraction

import numba
import numpy as np
import pytest

from core import Mesh, RenderSettings, Scene, TriangleMesh
from core.compile import compile_scene
from core.kernels.bvh_wide import WIDTH
from core.kernels.shapes import NO_HIT
from core.kernels.slabs import INF32, SLAB_SLACK, SLAB_SLACK32, box_entry, child_entries, slab_ray
from core.kernels.triangles import LEAF_WIDTH
from core.kernels.vec import inverse
from tests.support.probe import hits

RNG = np.random.default_rng(11)


@numba.njit(error_model="numpy")  # 1 / 0 is inf, as in the kernels
def entries32(boxes, origins, directions, t_min, t_max, whole_line):
    """child_entries of node 0 of `boxes` (1, 6, WIDTH) for each ray (float32 distances)."""
    out = np.empty((origins.shape[0], WIDTH), np.float32)
    for r in range(origins.shape[0]):
        o = (origins[r, 0], origins[r, 1], origins[r, 2])
        d = (directions[r, 0], directions[r, 1], directions[r, 2])
        e = child_entries(boxes, 0, slab_ray(o, d, whole_line), t_min[r], t_max[r])
        for c in range(WIDTH):
            out[r, c] = e[c]
    return out


@numba.njit(error_model="numpy")
def entries64(bounds, origins, directions, t_min, t_max):
    """box_entry of box 0 of `bounds` (1, 6) for each ray."""
    out = np.empty(origins.shape[0])
    for r in range(origins.shape[0]):
        o = (origins[r, 0], origins[r, 1], origins[r, 2])
        d = (directions[r, 0], directions[r, 1], directions[r, 2])
        out[r] = box_entry(bounds, 0, o, inverse(d), t_min[r], t_max[r])
    return out


def exact_entry(o, d, lo, hi, t_min, t_max):
    """The exact entry distance of o + t d, t_min <= t <= t_max (None for no bound), into the
    closed box [lo, hi] (all values taken as the exact rationals their floats are), or None
    on a miss."""
    near = None if t_min is None else Fraction(t_min)
    far = None if t_max is None else Fraction(t_max)
    for a in range(3):
        oa, da = Fraction(o[a]), Fraction(d[a])
        la, ha = Fraction(float(lo[a])), Fraction(float(hi[a]))
        if da == 0:
            if not la <= oa <= ha:
                return None
            continue
        t0, t1 = sorted(((la - oa) / da, (ha - oa) / da))
        near = t0 if near is None else max(near, t0)
        far = t1 if far is None else min(far, t1)
    if near is None:  # a line parallel to every axis cannot be: d is a unit vector
        raise AssertionError(d)
    return near if far is None or near <= far else None


def grazing_rays(box_lo, box_hi, count):
    """Rays aimed at points on the box's boundary (corners, edge and face points, exact in
    float32) from origins 1e-3 to 1e300 away: rounding puts them a hair inside or outside."""
    which = RNG.integers(0, 2, size=(count, 3))
    target = np.where(which == 1, box_hi, box_lo).astype(np.float64)
    # Free one or two coordinates to slide along an edge or across a face
    free = RNG.random((count, 3)) < 0.3
    inside = RNG.uniform(box_lo, box_hi, size=(count, 3)).astype(np.float32)
    target = np.where(free, inside, target)
    # Mostly near enough that rounding leaves the ray within a hair of the target
    distance = 10.0 ** np.where(
        RNG.random(count) < 0.8, RNG.uniform(-3, 4, size=count), RNG.uniform(4, 300, size=count)
    )
    # Some axis-parallel rays, some with a tiny component (inverse beyond float32's range)
    direction = RNG.normal(size=(count, 3))
    flat = RNG.random((count, 3)) < 0.1
    direction[flat] = 0.0
    tiny = RNG.random((count, 3)) < 0.05
    direction[tiny] *= 1e-42
    direction[np.all(direction == 0.0, axis=1), 2] = 1.0
    direction /= np.linalg.norm(direction, axis=1, keepdims=True)
    origins = target - direction * distance[:, None]
    return origins, direction, distance * (1.0 + RNG.uniform(-1e-6, 1.0, size=count))


def random_boxes(count):
    """`count` boxes (3, count) of float32 corners, of every size, anywhere."""
    centre = RNG.normal(size=3) * 10.0 ** RNG.uniform(-3, 5)
    half = np.abs(RNG.normal(size=(3, count))) * 10.0 ** RNG.uniform(-6, 3)
    return (centre[:, None] - half).astype(np.float32), (centre[:, None] + half).astype(np.float32)


def queries(lo, hi, whole_line):
    """Grazing rays at the box [lo, hi] with their t bounds (float64); as whole lines, half
    of them turned round, so that the box lies behind the origin."""
    o, d, t_max = grazing_rays(lo, hi, 60)
    t_min = np.zeros(len(o))
    if whole_line:
        d[::2] *= -1.0
        t_min, t_max = np.full(len(o), -np.inf), np.full(len(o), np.inf)
    return o, d, t_min, t_max


def float32_bounds(t_min, t_max):
    """The float32 bounds a traversal passes: t_min rounded down, t_max up."""
    with np.errstate(over="ignore"):
        lo32, hi32 = t_min.astype(np.float32), t_max.astype(np.float32)
    lo32 = np.where(lo32 > t_min, np.nextafter(lo32, np.float32(-np.inf)), lo32)
    hi32 = np.where(hi32 < t_max, np.nextafter(hi32, np.float32(np.inf)), hi32)
    return lo32, hi32


def check_conservative(found, missed, exact, slack, context):
    """A box the exact query meets is not culled, and its entry is not later than the exact
    entry widened by `slack`. Returns whether the exact query meets it."""
    if exact is None:
        return False
    assert found != missed, context
    exact_widened = exact + abs(exact) * Fraction(float(slack))
    assert found == -np.inf or Fraction(float(found)) <= exact_widened, context
    return True


@pytest.mark.parametrize("whole_line", [False, True], ids=["ray", "line"])
def test_the_float32_slab_test_never_culls_a_box_the_exact_query_meets(whole_line):
    checked = met = 0
    for _ in range(40):
        lo, hi = random_boxes(WIDTH)
        boxes = np.concatenate([lo, hi])[None, :, :].astype(np.float32)
        for c in range(WIDTH):
            o, d, t_min, t_max = queries(lo[:, c], hi[:, c], whole_line)
            found = entries32(boxes, o, d, *float32_bounds(t_min, t_max), whole_line)[:, c]
            for r in range(len(o)):
                bounds = [None if np.isinf(t) else t for t in (t_min[r], t_max[r])]
                exact = exact_entry(o[r], d[r], lo[:, c], hi[:, c], *bounds)
                context = (o[r], d[r], lo[:, c], hi[:, c])
                met += check_conservative(found[r], INF32, exact, SLAB_SLACK32, context)
                checked += 1
    # The rays graze: a fair share meets the box exactly, a fair share misses
    assert 0.2 * checked < met < 0.8 * checked, met / checked


@pytest.mark.parametrize("whole_line", [False, True], ids=["ray", "line"])
def test_the_float64_slab_test_never_culls_a_box_the_exact_query_meets(whole_line):
    checked = met = 0
    for _ in range(300):
        lo, hi = random_boxes(1)
        lo, hi = lo[:, 0], hi[:, 0]
        bounds = np.concatenate([lo, hi]).astype(np.float64)[None, :]
        o, d, t_min, t_max = queries(lo, hi, whole_line)
        found = entries64(bounds, o, d, t_min, t_max)
        for r in range(len(o)):
            limits = [None if np.isinf(t) else t for t in (t_min[r], t_max[r])]
            exact = exact_entry(o[r], d[r], lo, hi, *limits)
            met += check_conservative(found[r], NO_HIT, exact, SLAB_SLACK, (o[r], d[r], lo, hi))
            checked += 1
    assert 0.2 * checked < met < 0.8 * checked, met / checked


def test_empty_slots_of_leaf_blocks_are_never_hit():
    """Five triangles fill one leaf and part of another: rays at every triangle, and rays
    all around, hit only filled slots, and each triangle is hit at its own slot."""
    # Five triangles side by side, none in front of another seen from +z
    v = RNG.uniform(0, 0.9, size=(5, 3, 3))
    v[:, :, 0] += np.arange(5)[:, None]
    mesh = TriangleMesh(v.reshape(15, 3), np.arange(15).reshape(5, 3))
    compiled = compile_scene(Scene(shapes=[Mesh(mesh=mesh)]), RenderSettings(8, 8))
    corners = compiled.packed.geometry.tri_corners
    filled = ~np.isnan(corners).any(axis=1).reshape(-1)  # per slot
    assert filled.sum() == 5 and len(filled) % LEAF_WIDTH == 0 and len(filled) > 5
    blocks_xyz = corners.transpose(0, 2, 1).reshape(-1, 3, 3)  # slot, corner, xyz
    centroids = blocks_xyz[filled].mean(axis=1)
    origins = centroids + (0.0, 0.0, 5.0)
    directions = np.tile((0.0, 0.0, -1.0), (len(centroids), 1))
    _, shape, part = hits(compiled.packed, origins, directions)
    assert np.all(shape == 0)
    np.testing.assert_array_equal(part, np.flatnonzero(filled))
    origins = RNG.normal(size=(4000, 3)) * 3.0
    directions = RNG.uniform((0, 0, 0), (5, 1, 1), size=(4000, 3)) - origins  # at the mesh's box
    _, shape, part = hits(compiled.packed, origins, directions)
    assert np.all(filled[part[shape == 0]]) and (shape == 0).sum() > 100
