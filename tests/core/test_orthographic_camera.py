"""Orthographic cameras against closed forms and the independent reference tracer."""

import dataclasses

import numpy as np
import pytest

from core import Camera, Material, RenderSettings, Scene, SceneError, Sphere, render
from tests.support.reference_tracer import orthographic_camera_ray, shade_ray
from tests.support.scenes import ball_on_ground, reference_of, translate_scale


def orthographic(scene, view_height, shift=(0.0, 0.0)):
    camera = dataclasses.replace(
        scene.camera, projection="orthographic", ortho_height=view_height, shift=shift
    )
    return dataclasses.replace(scene, camera=camera)


@pytest.mark.parametrize("shift", [(0.0, 0.0), (0.3, -0.2)])
def test_pixels_match_the_reference_tracer(shift):
    scene = orthographic(ball_on_ground(), 9.0, shift)
    width, height = 96, 72
    image = render(scene, RenderSettings(width, height, tile_size=16, pixel_samples=1)).image
    spheres, lights = reference_of(scene)
    cam = scene.camera
    rng = np.random.default_rng(5)
    for px, py in rng.integers((0, 0), (width, height), size=(150, 2)):
        o, d = orthographic_camera_ray(cam.eye, cam.view, cam.up, 9.0, width, height, px, py,
                                       shift)  # fmt: skip
        expected = shade_ray(spheres, lights, scene.ambient, scene.background, o, d)
        np.testing.assert_allclose(image[py, px, :3], expected, rtol=2e-5, atol=2e-6)


def test_a_sphere_is_a_disc_of_its_own_radius_at_any_distance():
    """Seen orthographically a sphere's silhouette is a disc of its radius, wherever the
    camera stands along the view: pixel centres inside the circle are covered, outside not
    (those within 1e-9 of the rim are left out)."""
    width, height, view_height, radius = 80, 60, 6.0, 1.7
    white = Material(diffuse=(1, 1, 1))
    for distance in (3.0, 40.0, 4000.0):
        scene = Scene(
            camera=Camera(eye=(0.4, -0.3, distance), view=(0, 0, -1), up=(0, 1, 0),
                          projection="orthographic", ortho_height=view_height),
            shapes=[Sphere("S", white, translate_scale((0.0, 0.0, 0.0), radius))],
            ambient=(1.0, 1.0, 1.0),
        )  # fmt: skip
        image = render(scene, RenderSettings(width, height, pixel_samples=1)).image
        scale = view_height / height
        x = 0.4 + (np.arange(width) + 0.5 - width / 2) * scale
        y = -0.3 - (np.arange(height) + 0.5 - height / 2) * scale
        r = np.hypot(*np.meshgrid(x, y))
        clear = np.abs(r - radius) > 1e-9
        covered = image[..., 0] > 0.5
        np.testing.assert_array_equal(covered[clear], (r < radius)[clear])
        assert covered.sum() > 500


def test_the_view_height_must_be_positive():
    camera = Camera(projection="orthographic", ortho_height=0.0, name="Top")
    with pytest.raises(SceneError, match=r"camera 'Top': ortho_height: .*"):
        camera.validate()
    with pytest.raises(SceneError, match=r"camera 'Top': projection: got 'fisheye'; use one of"):
        Camera(projection="fisheye", name="Top").validate()
