"""The lens's polygonal aperture (`light_samples.regular_polygon`, Camera › Aperture ›
Blades): the unit square maps onto the regular polygon with its corners on the unit circle,
evenly. Checked against the polygon's closed forms: every point inside it, an equal share in
each of its triangles, its centre and polar moment; the corners where Blender's Rotation puts
them. (Cycles' blur through the same aperture: tests/blender/test_cycles_camera.py.)"""

import math

import numpy as np
import pytest

from core.kernels.light_samples import regular_polygon


def points(corners, rotation, count=40_000, seed=3):
    uv = np.random.default_rng(seed).random((count, 2))
    return np.array([regular_polygon(corners, rotation, a, b) for a, b in uv])


def inside(xy, corners, rotation):
    """Whether each point is inside the polygon: within the inner radius along each edge's
    normal (the edges' normals point at angles rotation + 2 pi k / n)."""
    inner = math.cos(math.pi / corners)
    normals = rotation + 2.0 * math.pi * np.arange(corners) / corners
    reach = xy @ np.stack([np.cos(normals), np.sin(normals)])
    return (reach <= inner + 1e-12).all(axis=1)


@pytest.mark.parametrize("corners, rotation", [(3, 0.0), (5, 0.3), (6, -1.2), (12, 2.0)])
def test_the_polygon_is_covered_evenly_and_never_left(corners, rotation):
    xy = points(corners, rotation)
    assert inside(xy, corners, rotation).all()
    # Even density: the mean at the centre, and the polar moment E[x^2 + y^2] of a uniform
    # regular n-gon of circumradius 1, (1/6)(2 + cos(2 pi / n))
    np.testing.assert_allclose(xy.mean(axis=0), 0.0, atol=0.01)
    polar = (2.0 + math.cos(2.0 * math.pi / corners)) / 6.0
    assert np.mean((xy**2).sum(axis=1)) == pytest.approx(polar, rel=0.01)
    # Each of the n triangles fanned from the centre holds 1/n of the points
    angles = np.mod(np.arctan2(xy[:, 1], xy[:, 0]) - rotation, 2.0 * math.pi)
    shares = np.bincount((angles / (2.0 * math.pi / corners)).astype(int), minlength=corners)
    np.testing.assert_allclose(shares / len(xy), 1.0 / corners, atol=0.01)


def test_the_corners_are_where_the_rotation_puts_them():
    """a's ends and b's reach the corners: rotation + (2k + 1) pi / n, on the unit circle."""
    corners, rotation = 5, 0.3
    for k in range(corners):
        x, y = regular_polygon(corners, rotation, (k + 1.0 - 1e-12) / corners, 0.0)
        angle = rotation + (2 * k + 1) * math.pi / corners
        assert (x, y) == pytest.approx((math.cos(angle), math.sin(angle)), abs=1e-5)
