"""Coloured shadows, against closed forms: what passes a surface straight (a Transparent
BSDF's colour, or its share of a mix) filters a shadow ray channel by channel, as Cycles
draws it (side by side in tests/blender/test_cycles_glass_shadows.py). A ball of
Transparent BSDF colour c over a floor lit straight down casts c^2 of the open floor in each
channel (two crossings), whatever the light (Blender's sun, the report's directional and
point lights) and under either glass-shadow rule; where the mix varies over the ball, each
pixel gets (f(x) c)^2 for the factor f at the crossings' x."""

import numpy as np
import pytest

from core import (
    Camera,
    DirectionalLight,
    Material,
    PointLight,
    RenderSettings,
    Scene,
    ShaderNode,
    Sphere,
    SunLight,
    render,
)
from tests.core.test_shadows_through_node_materials import x_mix_material

RED = (1.0, 0.3, 0.1)
SIZE = 32
VIEW = 4.0


def _floor_under(ball_material, light, rule="blocked", passes=()):
    """A grey floor (z = -2) seen from straight above, the unit ball at the origin hidden
    from the camera: (the picture, RGB; each pixel's x; its distance from the axis)."""
    lowered = np.diag([50.0, 50.0, 1e-3, 1.0])
    lowered[2, 3] = -2.0
    floor = Sphere("Floor", Material(diffuse=(0.8, 0.8, 0.8)), lowered)
    ball = Sphere("Ball", ball_material, np.eye(4))
    ball.seen_by_camera = False
    camera = Camera(eye=(0.0, 0.0, 10.0), view=(0.0, 0.0, -1.0), up=(0.0, 1.0, 0.0),
                    projection="orthographic", ortho_height=VIEW)  # fmt: skip
    scene = Scene(shapes=[floor, ball], lights=[light], camera=camera)
    settings = RenderSettings(SIZE, SIZE, pixel_samples=1, glass_shadows=rule, max_depth=0,
                              passes=passes)  # fmt: skip
    out = render(scene, settings)
    centre = (np.arange(SIZE) + 0.5) / SIZE * VIEW - VIEW / 2.0
    x, y = np.meshgrid(centre, -centre)
    return out, x, np.hypot(x, y)


LIGHTS = {
    "sun": SunLight(name="Sun", direction=(0.0, 0.0, -1.0), irradiance=(3.0, 3.0, 3.0)),
    "report_directional": DirectionalLight(direction=(0.0, 0.0, -1.0), intensity=(0.9,) * 3),
    # far above: its rays through the ball all but vertical (a constant colour needs not)
    "report_point": PointLight(position=(0.0, 0.0, 40.0), intensity=(0.9,) * 3),
}


@pytest.mark.parametrize("rule", ["attenuated", "blocked"])
@pytest.mark.parametrize("light", sorted(LIGHTS))
def test_a_coloured_transparent_ball_casts_its_colour_squared(light, rule):
    veil = Material(name="Veil", diffuse=(0.0, 0.0, 0.0),
                    surface=ShaderNode("transparent", {"Color": RED}))  # fmt: skip
    out, _, radius = _floor_under(veil, LIGHTS[light], rule)
    image = out.image[..., :3].astype(float)
    if light == "report_point":  # the floor lit by I cos, cos = 42 / distance, made even
        image /= (42.0 / np.hypot(42.0, radius))[..., None]
    lit = image[radius > 1.1].mean(axis=0)
    assert lit.min() > 0.1
    expected = lit * np.square(RED)
    np.testing.assert_allclose(image[radius < 0.9], np.broadcast_to(expected, (
        (radius < 0.9).sum(), 3)), rtol=2e-6, atol=1e-7)  # fmt: skip


def test_a_varying_coloured_mix_casts_its_colour_at_each_crossing():
    """Transparent BSDF (red) mixed into Diffuse by 0.5 + 0.4 X: straight down through the
    ball both crossings sit at the pixel's x, so each channel passes ((0.5 + 0.4 x) c)^2."""
    mix = x_mix_material(ShaderNode("transparent", {"Color": RED}))
    out, x, radius = _floor_under(mix, LIGHTS["sun"])
    image = out.image[..., :3].astype(float)
    lit = image[radius > 1.1].mean(axis=0)
    inside = radius < 0.9
    factor = (0.5 + 0.4 * x[inside])[:, None] * np.array(RED)
    np.testing.assert_allclose(image[inside], lit * factor**2, rtol=2e-6, atol=1e-7)


def test_the_shadow_pass_holds_the_colour():
    """The Shadow pass (light with shadows over light without) is the colour squared."""
    veil = Material(name="Veil", diffuse=(0.0, 0.0, 0.0),
                    surface=ShaderNode("transparent", {"Color": RED}))  # fmt: skip
    out, _, radius = _floor_under(veil, LIGHTS["sun"], passes=("shadow",))
    shadow = out.passes["shadow"][..., :3]
    np.testing.assert_allclose(shadow[radius < 0.9], np.broadcast_to(np.square(RED), (
        (radius < 0.9).sum(), 3)), rtol=1e-5)  # fmt: skip
    np.testing.assert_allclose(shadow[radius > 1.1], 1.0, rtol=1e-5)


def test_grey_shadows_are_unchanged_by_the_colour_rule():
    """A grey veil's shadow is its grey squared, channel for channel the same number."""
    veil = Material(name="Veil", diffuse=(0.0, 0.0, 0.0),
                    surface=ShaderNode("transparent", {"Color": (0.6,) * 3}))  # fmt: skip
    out, _, radius = _floor_under(veil, LIGHTS["report_point"])
    inside = out.image[..., :3][radius < 0.9]
    assert np.all(inside[:, 0] == inside[:, 1]) and np.all(inside[:, 1] == inside[:, 2])
