"""Hit distances, normals and UVs of every analytic shape under random affine transforms,
against world-space references (tests/reference_shapes.py) and closed-form points."""

import math

import numpy as np
import pytest

from core import Box, Cone, Cylinder, Sphere, Torus
from tests.support.probe import hits, packed_shapes, surface
from tests.support.reference_shapes import (
    constraint_normal,
    first_crossing,
    random_affine,
    torus_roots_mp,
    world_constraints,
)

RNG = np.random.default_rng(20261121)
SHAPES = {"sphere": Sphere, "box": Box, "cylinder": Cylinder, "cone": Cone}


def near_an_edge(quadric, planes, label, point, tolerance=1e-6):
    """Whether a constraint other than `label` is nearly active at `point`: the hit is on or
    next to a rim or corner, where hit or miss is decided by rounding."""
    x = np.append(point, 1.0)
    scale = 1.0 + np.abs(point).max()
    for k, a in enumerate(planes):
        if k != label and abs(a @ x) < tolerance * scale * np.linalg.norm(a[:3]):
            return True
    if quadric is not None and label != "q":
        g = np.linalg.norm((quadric @ x)[:3])
        if abs(x @ quadric @ x) < tolerance * scale * max(g, 1e-300):
            return True
    return False


@pytest.mark.parametrize("kind", SHAPES)
@pytest.mark.parametrize("trial", range(3))
def test_convex_shapes_match_the_world_space_reference(kind, trial):
    matrix = random_affine(RNG)
    packed = packed_shapes(SHAPES[kind](world_from_object=matrix))
    quadric, planes = world_constraints(kind, matrix)
    centre = matrix[:3, 3]
    origins = centre + RNG.normal(size=(300, 3)) * 40.0
    # Every fifth ray starts inside the shape
    origins[::5] = centre + (matrix[:3, :3] @ RNG.uniform(-0.3, 0.3, size=(60, 3)).T).T
    targets = centre + (matrix[:3, :3] @ RNG.uniform(-1.3, 1.3, size=(300, 3)).T).T
    directions = targets - origins
    directions /= np.linalg.norm(directions, axis=1, keepdims=True)
    t_all, shape_all, _ = hits(packed, origins, directions)
    checked = 0
    for o, d, t, shape in zip(origins, directions, t_all, shape_all, strict=True):
        expected = first_crossing(quadric, planes, o, d)
        if expected is not None and near_an_edge(quadric, planes, expected[1], o + expected[0] * d):
            continue
        if expected is None:
            assert shape == -1, f"ray {o} -> {d} should miss, got t={t}"
            continue
        assert shape == 0, f"ray {o} -> {d} should hit at {expected[0]}"
        assert t == pytest.approx(expected[0], rel=1e-9, abs=1e-9)
        _, _, point, normal, _, _ = surface(packed, o, d)
        np.testing.assert_allclose(
            normal, constraint_normal(quadric, planes, expected[1], point), atol=1e-7
        )
        checked += 1
    assert checked > 100


def torus_case(rng, case):
    """(origin, direction) in object space of the torus R = 1, r = 0.25, for one case."""
    if case == "grazing":
        # Aim at a point on the tube's silhouette seen from far away, plus a tiny offset
        angle = rng.uniform(0, 2 * math.pi)
        origin = rng.normal(size=3) * 20.0
        tube_centre = np.array([math.cos(angle), math.sin(angle), 0.0])
        to_tube = tube_centre - origin
        side = np.cross(to_tube, rng.normal(size=3))
        side /= np.linalg.norm(side)
        target = tube_centre + side * 0.25 * (1.0 + rng.uniform(-1e-5, 1e-5))
        return origin, target - origin
    if case == "axis":
        origin = np.array([*rng.uniform(-1.4, 1.4, size=2), 30.0])
        return origin, np.array([*rng.normal(size=2) * 1e-3, -1.0])
    if case == "far":
        direction = rng.normal(size=3)
        direction /= np.linalg.norm(direction)
        origin = -direction * 1.25e4 + rng.normal(size=3) * 0.8
        return origin, direction
    # inside the tube
    angle = rng.uniform(0, 2 * math.pi)
    offset = rng.normal(size=3)
    offset *= rng.uniform(0, 0.24) / np.linalg.norm(offset)
    origin = np.array([math.cos(angle), math.sin(angle), 0.0]) + offset
    return origin, rng.normal(size=3)


@pytest.mark.parametrize("seed, case", list(enumerate(["grazing", "axis", "far", "inside"])))
def test_torus_against_sixty_digit_roots(seed, case):
    rng = np.random.default_rng(seed)
    packed = packed_shapes(Torus(major_radius=1.0, minor_radius=0.25))
    rays = [torus_case(rng, case) for _ in range(150)]
    origins = np.array([o for o, _ in rays])
    directions = np.array([d / np.linalg.norm(d) for _, d in rays])
    t_all, shape_all, _ = hits(packed, origins, directions)
    checked = skipped = 0
    for o, d, t, shape in zip(origins, directions, t_all, shape_all, strict=True):
        roots, gap = torus_roots_mp(o, d, 1.0, 0.25)
        if gap < 1e-7:
            skipped += 1
            continue  # within the band around tangency
        ahead = [r for r in roots if r > 0]
        if not ahead:
            assert shape == -1, f"ray {o} -> {d} should miss the torus, got t={t}"
            continue
        assert shape == 0, f"ray {o} -> {d} should hit the torus at {ahead[0]}"
        assert t == pytest.approx(ahead[0], rel=1e-9)
        checked += 1
    assert checked > 50, f"{skipped} rays were within the tangency band"


def test_transformed_torus_normal_is_the_tube_normal():
    matrix = random_affine(RNG, translate=5.0)
    packed = packed_shapes(Torus(world_from_object=matrix, major_radius=2.0, minor_radius=0.5))
    inverse = np.linalg.inv(matrix)
    for _ in range(50):
        o = matrix[:3, 3] + RNG.normal(size=3) * 30
        d = matrix[:3, 3] + matrix[:3, :3] @ RNG.uniform(-2, 2, size=3) - o
        found = surface(packed, o, d / np.linalg.norm(d))
        if found is None:
            continue
        _, _, point, normal, _, _ = found
        p = inverse[:3, :3] @ point + inverse[:3, 3]
        core_point = 2.0 * np.array([p[0], p[1], 0.0]) / math.hypot(p[0], p[1])
        assert np.linalg.norm(p - core_point) == pytest.approx(0.5, rel=1e-9)
        expected = inverse[:3, :3].T @ (p - core_point)
        np.testing.assert_allclose(normal, expected / np.linalg.norm(expected), atol=1e-9)


@pytest.mark.parametrize(
    "shape, origin, direction, uv",
    [
        (Sphere(), (5, 0, 0), (-1, 0, 0), (0.5, 0.5)),  # +x on the equator
        (Sphere(), (0, 5, 0), (0, -1, 0), (0.75, 0.5)),  # +y: a quarter turn on
        (Sphere(), (0, 0, 5), (0, 0, -1), (None, 1.0)),  # north pole
        (Sphere(), (0, 0, 0), (0, 0, -1), (None, 0.0)),  # south pole, from inside
        (Box(), (5, 0.5, -0.5), (-1, 0, 0), (0.75, 0.25)),  # +x face: u along +y, v along z
        (Box(), (-0.5, 0.5, 5), (0, 0, -1), (0.25, 0.75)),  # top face: u along x, v along y
        (Cylinder(), (0.5, 0.5, 5), (0, 0, -1), (0.75, 0.75)),  # top cap: planar
        (Cylinder(), (5, 0, 0.5), (-1, 0, 0), (0.5, 0.75)),  # side: around and up
        (Cone(), (0, 5, -0.5), (0, -1, 0), (0.75, 0.25)),  # side, where radius is 0.75
        (Cone(), (0.5, 0.0, -5), (0, 0, 1), (0.75, 0.5)),  # base cap
        (Torus(), (5, 0, 0), (-1, 0, 0), (0.5, 0.5)),  # outer equator at +x
        (Torus(), (1, 0, 5), (0, 0, -1), (0.5, 0.75)),  # top of the tube: a quarter turn
    ],
)
def test_uv_at_closed_form_points(shape, origin, direction, uv):
    _, _, _, _, _, (u, v) = surface(packed_shapes(shape), origin, direction)
    if uv[0] is not None:
        assert u == pytest.approx(uv[0], abs=1e-12)
    assert v == pytest.approx(uv[1], abs=1e-12)


def test_uv_is_continuous_on_the_sphere_away_from_the_seam():
    packed = packed_shapes(Sphere())
    previous = None
    for angle in np.linspace(-3.0, 3.0, 200):
        d = -np.array([math.cos(angle), math.sin(angle), 0.3])
        _, _, _, _, _, (u, v) = surface(packed, -5 * d, d)
        if previous is not None:
            assert abs(u - previous) < 0.01
        previous = u
        assert v == pytest.approx(0.5 + math.asin(0.3 / math.hypot(1, 0.3)) / math.pi)
