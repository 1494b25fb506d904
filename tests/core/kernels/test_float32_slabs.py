"""The mesh BVH's float32 slab test (core.kernels.bvh_wide) is conservative, checked against
exact rational arithmetic: it never culls a box that the exact float64 ray meets, and the
entry distance it reports exceeds the exact one by no more than SLAB_WIDEN32, which is what
nearest-hit traversal relies on when it skips a waiting box. The rays graze boxes at their
corners, edges and faces from origins of every magnitude, beyond float32's range included.
Also: the slots a leaf block leaves empty are never hit."""

from fractions import Fraction

import numba
import numpy as np

from core import Mesh, RenderSettings, Scene, TriangleMesh
from core.compile import compile_scene
from core.kernels.bvh_wide import INF32, SLAB_WIDEN32, WIDTH, child_entries, slab_ray
from core.kernels.triangles import LEAF_WIDTH
from tests.support.probe import hits

RNG = np.random.default_rng(11)


@numba.njit(error_model="numpy")  # 1 / 0 is inf, as in the kernels
def entries(boxes, origins, directions, t_max):
    """child_entries of node 0 of `boxes` (1, 6, WIDTH) for each ray (float32 distances)."""
    out = np.empty((origins.shape[0], WIDTH), np.float32)
    for r in range(origins.shape[0]):
        o = (origins[r, 0], origins[r, 1], origins[r, 2])
        d = (directions[r, 0], directions[r, 1], directions[r, 2])
        e = child_entries(boxes, 0, slab_ray(o, d), np.float32(0.0), t_max[r])
        for c in range(WIDTH):
            out[r, c] = e[c]
    return out


def exact_entry(o, d, lo, hi, t_max):
    """The exact entry distance of the ray o + t d, 0 <= t <= t_max, into the closed box
    [lo, hi] (all values taken as the exact rationals their floats are), or None on a miss."""
    near, far = Fraction(0), Fraction(t_max)
    for a in range(3):
        oa, da = Fraction(o[a]), Fraction(d[a])
        la, ha = Fraction(float(lo[a])), Fraction(float(hi[a]))
        if da == 0:
            if not la <= oa <= ha:
                return None
            continue
        t0, t1 = sorted(((la - oa) / da, (ha - oa) / da))
        near, far = max(near, t0), min(far, t1)
    return near if near <= far else None


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


def test_the_float32_slab_test_never_culls_a_box_the_exact_ray_meets():
    checked = met = 0
    for _ in range(40):
        centre = RNG.normal(size=3) * 10.0 ** RNG.uniform(-3, 5)
        half = np.abs(RNG.normal(size=(3, WIDTH))) * 10.0 ** RNG.uniform(-6, 3)
        lo = (centre[:, None] - half).astype(np.float32)
        hi = (centre[:, None] + half).astype(np.float32)
        boxes = np.concatenate([lo, hi])[None, :, :].astype(np.float32)
        for c in range(WIDTH):
            o, d, t_max = grazing_rays(lo[:, c], hi[:, c], 60)
            with np.errstate(over="ignore"):
                t_max32 = t_max.astype(np.float32)  # rounded up, as the traversal does
            t_max32 = np.where(t_max32 < t_max, np.nextafter(t_max32, np.float32(np.inf)), t_max32)
            found = entries(boxes, o, d, t_max32)[:, c]
            for r in range(len(o)):
                exact = exact_entry(o[r], d[r], lo[:, c], hi[:, c], t_max[r])
                checked += 1
                if exact is None:
                    continue
                met += 1
                assert found[r] != INF32, (o[r], d[r], lo[:, c], hi[:, c])
                assert Fraction(float(found[r])) <= exact * Fraction(float(SLAB_WIDEN32))
    # The rays graze: a fair share meets the box exactly, a fair share misses
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
