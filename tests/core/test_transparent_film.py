"""Film > Transparent (RenderSettings.transparent): a pixel's alpha is the share of its
camera rays that meet something, checked against an exact ray-sphere test of each grid
sample in plain Python; colour is premultiplied (nothing where nothing is met); mirrors still
show the background, as in Cycles; and without it, every pixel is opaque as before."""

import math

import numpy as np

import core
from core import Camera, Material, RenderSettings, Scene, Sphere
from tests.support.reference_tracer import camera_ray
from tests.support.scenes import LIGHT, translate_scale

CENTRE, RADIUS = np.array([0.3, -0.2, 0.0]), 1.1
CAMERA = Camera(eye=(0.0, 0.0, 6.0), view=(0.0, 0.0, -1.0), up=(0.0, 1.0, 0.0), fovy=40.0)
N = 4  # 4 x 4 grid camera rays per pixel
WIDTH, HEIGHT = 32, 24


def sphere_scene(material=None):
    ball = Sphere("Ball", material or Material(), translate_scale(CENTRE, RADIUS))
    return Scene(CAMERA, [ball], [LIGHT], ambient=(0.1, 0.1, 0.1), background=(0.2, 0.4, 0.8))


def exact_alpha(px, py):
    """Share of pixel (px, py)'s grid samples whose ray meets the ball, and whether any
    sample grazes it too closely for float64 to decide."""
    hits, close = 0, False
    for s in range(N * N):
        fx, fy = (s % N + 0.5) / N, (s // N + 0.5) / N
        o, d = camera_ray(CAMERA.eye, CAMERA.view, CAMERA.up, CAMERA.fovy, WIDTH, HEIGHT,
                          px + fx - 0.5, py + fy - 0.5)  # fmt: skip
        oc = o - CENTRE
        b = float(np.dot(d, oc))
        discriminant = b * b - (float(np.dot(oc, oc)) - RADIUS**2)
        close |= abs(discriminant) < 1e-9
        hits += discriminant > 0.0 and -b - math.sqrt(max(discriminant, 0.0)) > 0.0
    return hits / (N * N), close


def test_alpha_is_the_exact_share_of_camera_rays_meeting_the_ball():
    settings = RenderSettings(width=WIDTH, height=HEIGHT, pixel_samples=N, transparent=True)
    image = core.render(sphere_scene(), settings).image
    fractional = 0
    for py in range(HEIGHT):
        for px in range(WIDTH):
            expected, close = exact_alpha(px, py)
            if close:
                continue
            assert image[py, px, 3] == np.float32(expected), (px, py)
            fractional += 0.0 < expected < 1.0
    assert fractional > 20  # the rim was sampled, not only inside and outside
    outside = image[..., 3] == 0.0
    assert outside.any() and np.all(image[outside, :3] == 0.0)  # premultiplied


def test_a_mirror_still_shows_the_background_under_a_transparent_film():
    mirror = Material(diffuse=(0.0, 0.0, 0.0), specular=(0.0, 0.0, 0.0), reflectivity=1.0)
    settings = RenderSettings(width=WIDTH, height=HEIGHT, pixel_samples=1, transparent=True)
    image = core.render(sphere_scene(mirror), settings).image
    rim = image[HEIGHT // 2, WIDTH // 2 + 4]  # inside the ball, reflecting the sky behind
    assert rim[3] == 1.0 and rim[2] > 0.1


def test_without_it_every_pixel_is_opaque_and_the_colours_are_the_same():
    opaque = RenderSettings(width=WIDTH, height=HEIGHT, pixel_samples=2)
    image = core.render(sphere_scene(), opaque).image
    assert np.all(image[..., 3] == 1.0)
    clear = core.render(sphere_scene(), RenderSettings(**{**opaque.__dict__, "transparent": True}))
    covered = clear.image[..., 3] == 1.0
    np.testing.assert_array_equal(clear.image[covered, :3], image[covered, :3])
