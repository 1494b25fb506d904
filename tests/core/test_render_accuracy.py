"""Rendered images against closed forms and the independent reference tracer."""

import math

import numpy as np
import pytest

from core import Camera, Material, PointLight, RenderSettings, Scene, Sphere, render
from tests.support.reference_tracer import camera_ray, nearest, shade_ray
from tests.support.scenes import ball_on_ground, reference_of, translate_scale

BACKGROUND = (0.0, 0.0, 0.0)


def silhouette_conic(centre, radius):
    """Image-plane (z=1 in camera space) conic of a sphere's silhouette: the cone of rays v
    tangent to the sphere satisfies (v.c)^2 = (|c|^2 - r^2)|v|^2."""
    c = np.asarray(centre, float)
    return np.outer(c, c) - (c @ c - radius**2) * np.eye(3)


def ellipse_area_and_perimeter(conic):
    """Area and perimeter of the ellipse x^T A x = 0, x = (u, v, 1)."""
    A = -conic  # interior where x^T A x < 0 once the quadratic part is positive definite
    A33 = A[:2, :2]
    centre = np.linalg.solve(A33, -A[:2, 2])
    k = -(centre @ A[:2, 2] + A[2, 2])  # (x - centre)^T A33 (x - centre) = k
    axes = np.sqrt(k / np.linalg.eigvalsh(A33))
    a, b = axes
    h = ((a - b) / (a + b)) ** 2
    perimeter = math.pi * (a + b) * (1 + 3 * h / (10 + math.sqrt(4 - 3 * h)))  # Ramanujan
    return math.pi * a * b, perimeter


@pytest.mark.parametrize(
    "centre, radius",
    [((0.0, 0.0, -10.0), 2.0), ((3.0, -1.5, -12.0), 2.5), ((-2.2, 1.0, -9.0), 1.5)],
)
def test_silhouette_pixel_count_matches_projection(centre, radius):
    width, height, fovy = 200, 150, 40.0
    scene = Scene(
        camera=Camera(eye=(0, 0, 0), view=(0, 0, -1), up=(0, 1, 0), fovy=fovy),
        shapes=[Sphere("S", Material(diffuse=(1, 1, 1)), translate_scale(centre, radius))],
        ambient=(1.0, 1.0, 1.0),
        background=BACKGROUND,
    )
    image = render(scene, RenderSettings(width, height, pixel_samples=1)).image
    covered = int(np.count_nonzero(image[..., 0] > 0.5))

    # Camera space looks down -z; flip to the z=1 image plane, then scale to pixels
    cam_centre = (centre[0], centre[1], -centre[2])
    area, perimeter = ellipse_area_and_perimeter(silhouette_conic(cam_centre, radius))
    half_h = math.tan(math.radians(fovy) / 2)
    pixels_per_unit = height / (2 * half_h)
    expected = area * pixels_per_unit**2
    rim = perimeter * pixels_per_unit
    # Within a pixel's width along the rim (the bound); in practice far closer
    assert abs(covered - expected) <= rim, (covered, expected, rim)
    assert abs(covered - expected) <= 0.25 * rim, (covered, expected, rim)


def test_pixels_match_the_reference_tracer():
    scene = ball_on_ground()
    settings = RenderSettings(96, 72, tile_size=16, pixel_samples=1)
    image = render(scene, settings).image
    spheres, lights = reference_of(scene)
    cam = scene.camera
    rng = np.random.default_rng(7)
    for px, py in rng.integers((0, 0), (96, 72), size=(150, 2)):
        o, d = camera_ray(cam.eye, cam.view, cam.up, cam.fovy, 96, 72, px, py)
        expected = shade_ray(spheres, lights, scene.ambient, scene.background, o, d)
        np.testing.assert_allclose(image[py, px, :3], expected, rtol=2e-5, atol=2e-6)


def test_shadow_where_geometry_says():
    """Ground pixels whose segment to the light passes through the ball are lit by ambient
    only; those whose segment clears it by a margin are lit directly."""
    scene = ball_on_ground(light_position=(2.0, 1.0, 9.0))
    width, height = 120, 90
    image = render(scene, RenderSettings(width, height, pixel_samples=1)).image
    spheres, _ = reference_of(scene)
    cam = scene.camera
    light = np.asarray(scene.lights[0].position)
    ball_centre, ball_radius = np.array([0.0, 0.0, 2.5]), 1.0
    ambient_only = 0.5 * 0.1
    shadowed = lit = 0
    for py in range(height):
        for px in range(width):
            o, d = camera_ray(cam.eye, cam.view, cam.up, cam.fovy, width, height, px, py)
            index, t = nearest(spheres, o, d)
            if index != 1:
                continue
            point = o + t * d
            # Distance from the ball's centre to the segment point -> light
            seg = light - point
            s = np.clip((ball_centre - point) @ seg / (seg @ seg), 0.0, 1.0)
            gap = np.linalg.norm(point + s * seg - ball_centre) - ball_radius
            if gap < -0.02:
                assert image[py, px, 0] == pytest.approx(ambient_only, abs=1e-6), (px, py)
                shadowed += 1
            elif gap > 0.02:
                # Lambert term of the unshadowed light, ground normal from its centre
                normal = (point - np.array([0.0, 0.0, -1e4])) / 1e4
                distance = np.linalg.norm(seg)
                direct = 0.5 * 120.0 * max(0.0, normal @ seg / distance) / (1 + distance**2)
                assert image[py, px, 0] == pytest.approx(ambient_only + direct, rel=1e-5), (px, py)
                lit += 1
    assert shadowed > 50 and lit > 1000


def test_light_behind_surface_and_attenuation():
    """Irradiance of a point light on a plane-like surface: kd I cos(theta) / (c0 + c2 d^2)."""
    light = PointLight((3.0, 0.0, 4.0), (50.0, 50.0, 50.0), (1.0, 0.0, 0.5))
    ground = Sphere("Ground", Material(diffuse=(0.5, 0.5, 0.5)), translate_scale((0, 0, -1e5), 1e5))
    scene = Scene(
        camera=Camera(eye=(0, 0, 10), view=(0, 0, -1), up=(0, 1, 0), fovy=30.0),
        shapes=[ground],
        lights=[light],
    )
    image = render(scene, RenderSettings(41, 41, pixel_samples=1)).image
    # The centre pixel looks straight down at the origin
    d = math.sqrt(3.0**2 + 4.0**2)
    expected = 0.5 * 50.0 * (4.0 / d) / (1.0 + 0.5 * d * d)
    assert image[20, 20, 0] == pytest.approx(expected, rel=1e-6)
