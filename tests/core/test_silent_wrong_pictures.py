"""Values that once rendered a wrong picture with exit 0 are refused by name, or rendered
right. A World (Color x Strength) or a light of 1e76, finite in float64, overflowed the
kernels' float32 to a white frame; a sphere of radius 1e308 around the camera vanished
(its object space, scaled by 1e-308, left rays whose squares underflow to zero)."""

import numpy as np
import pytest

from core import (
    MAX_EXTENT,
    MAX_LIGHT,
    Camera,
    Environment,
    Material,
    PointLight,
    RenderSettings,
    Scene,
    SceneError,
    Sphere,
    SunLight,
    render,
)
from tests.support.scenes import translate_scale

GREY = Material(diffuse=(0.5, 0.5, 0.5), specular=(0.0, 0.0, 0.0), name="grey")
CAMERA = Camera(eye=(0.0, 0.0, 0.0), view=(0.0, 1.0, 0.0), up=(0.0, 0.0, 1.0), fovy=60.0)
TINY = RenderSettings(width=4, height=4)


def around_the_camera(radius: float, **scene) -> Scene:
    """A grey sphere of `radius` about the eye, lit by the ambient term alone."""
    shapes = [Sphere("Dome", GREY, translate_scale((0.0, 0.0, 0.0), radius))]
    return Scene(CAMERA, shapes, [], **{"ambient": (1.0, 1.0, 1.0), **scene})


@pytest.mark.parametrize(
    "scene, owner, field",
    [
        (around_the_camera(1.0, environment=Environment(colour=(1e76,) * 3)), "world 'World'",
         "colour"),
        (around_the_camera(1.0, environment=Environment(colour=(2 * MAX_LIGHT, 0, 0))),
         "world 'World'", "colour"),
        (around_the_camera(1.0, background=(1e39, 0.0, 0.0)), "scene", "background"),
        (around_the_camera(1.0, ambient=(1e30, 1e30, 1e30)), "scene", "ambient"),
        (Scene(CAMERA, [], [PointLight((0, 0, 0), (1e76, 0, 0), (1, 0, 0), name="Hot")]),
         "light 'Hot'", "intensity"),
        (Scene(CAMERA, [], [SunLight(direction=(0, 0, -1), irradiance=(1e40,) * 3, name="Sol")]),
         "sun 'Sol'", "irradiance"),
        (around_the_camera(1e308), "sphere 'Dome'", "transform"),
        (around_the_camera(1e200), "sphere 'Dome'", "transform"),
        (around_the_camera(2 * MAX_EXTENT), "sphere 'Dome'", "transform"),
    ],
)  # fmt: skip
def test_a_value_past_what_the_kernels_carry_is_refused_by_name(scene, owner, field):
    with pytest.raises(SceneError) as error:
        render(scene, TINY)
    assert error.value.owner == owner and error.value.field == field, str(error.value)


@pytest.mark.parametrize("radius", [1.0, 1e10, 1e20, MAX_EXTENT / 2])
def test_a_sphere_about_the_eye_of_any_allowed_size_is_drawn(radius):
    """Closed form: ambient 1 times diffuse 0.5 in every pixel (before: radius 1e200 and
    beyond gave a white frame or none)."""
    image = render(around_the_camera(radius), TINY).image
    assert np.allclose(image[..., :3], 0.5, atol=1e-6) and np.all(image[..., 3] == 1.0)


def test_the_brightest_light_allowed_renders_finitely():
    scene = around_the_camera(1.0, environment=Environment(colour=(MAX_LIGHT,) * 3))
    scene.shapes = []
    image = render(scene, TINY).image
    assert np.all(np.isfinite(image)) and np.allclose(image[..., :3], MAX_LIGHT, rtol=1e-6)
