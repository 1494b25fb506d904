"""Hit points and normals of transformed spheres against the closed-form quadric solution."""

import numpy as np
import pytest

from core import Sphere
from tests.support.probe import hit, packed_shapes, surface
from tests.support.reference_tracer import intersect_quadric, quadric_normal, sphere_quadric

RNG = np.random.default_rng(20261121)


def random_affine(rng):
    """Rotation times non-uniform scale (0.2..5), translated: a random ellipsoid."""
    q, _ = np.linalg.qr(rng.normal(size=(3, 3)))
    m = np.eye(4)
    m[:3, :3] = q @ np.diag(rng.uniform(0.2, 5.0, size=3))
    m[:3, 3] = rng.uniform(-50, 50, size=3)
    return m


@pytest.mark.parametrize("trial", range(5))
def test_hits_and_normals_match_the_quadric(trial):
    matrix = random_affine(RNG)
    packed = packed_shapes(Sphere(world_from_object=matrix))
    Q = sphere_quadric(matrix)
    centre = matrix[:3, 3]
    checked = 0
    for _ in range(400):
        origin = centre + RNG.normal(size=3) * 40.0
        # Aim near the ellipsoid so that about half the rays hit
        target = centre + matrix[:3, :3] @ RNG.uniform(-1.3, 1.3, size=3)
        direction = (target - origin) / np.linalg.norm(target - origin)
        roots = intersect_quadric(Q, origin, direction)
        shape, t, *_ = hit(packed, origin, direction)
        expected = None
        if roots is not None:
            expected = next((r for r in roots if r > 0), None)
        if roots is not None and abs(roots[1] - roots[0]) < 1e-6 * max(1.0, abs(roots[0])):
            continue  # hit-or-miss is ill-conditioned exactly at the silhouette
        if expected is None:
            assert shape == -1, f"ray from {origin} should miss, got t={t}"
            continue
        assert shape == 0
        assert t == pytest.approx(expected, rel=1e-9, abs=1e-9)
        _, _, point, n, _, _ = surface(packed, origin, direction)
        np.testing.assert_allclose(n, quadric_normal(Q, point), atol=1e-7)
        checked += 1
    assert checked > 100


def test_ray_starting_inside_hits_the_far_side():
    shape, t, *_ = hit(packed_shapes(Sphere()), (0.0, 0.0, 0.0), (1.0, 0.0, 0.0))
    assert shape == 0 and t == pytest.approx(1.0, abs=1e-15)


def test_distant_sphere_is_hit_precisely():
    """Far from the origin the stable discriminant keeps full precision (RTG chapter 7)."""
    matrix = np.eye(4)
    matrix[:3, 3] = (0.0, 0.0, -1e6)
    packed = packed_shapes(Sphere(world_from_object=matrix))
    shape, t, *_ = hit(packed, (0.0, 0.0, 0.0), (0.0, 0.0, -1.0))
    assert shape == 0 and t == pytest.approx(1e6 - 1.0, abs=1e-9)
