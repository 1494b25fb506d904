"""Shadows through glass, side by side with Cycles (tests/support/cycles.py): a ball hidden
from the camera hangs over the white plane in a sun straight above, so the plane under it
shows the ball's shadow alone. Under Whitted's default glass-shadow rule (Render > Light
Paths > Glass Shadows: Blocked) a Glass BSDF or a Principled BSDF of Transmission 1 casts a
full shadow, as in Cycles, whose shadow rays stop at refracting surfaces (the light they
would pass is caustics, which Cycles with diffuse bounces 0 does not draw on the plane);
a Transparent BSDF passes its colour at each crossing in both. The classic rule
(Attenuated) lets light through glass and disagrees with Cycles there: the test can tell."""

import math
import sys

import numpy as np
import pytest

from tests.support.cycles import (
    SIZE,
    VIEW,
    add_ball,
    add_light,
    new_scene,
    node_material,
    render_with,
)

pytestmark = pytest.mark.bpy

RADIUS = 1.0
TOLERANCE = 0.02  # of the open plane's brightness


def _glass(bpy):
    return node_material(bpy, "Glass", "ShaderNodeBsdfGlass", Roughness=0.0, IOR=1.5)[0]


def _principled_transmission(bpy):
    return node_material(bpy, "Clear", "ShaderNodeBsdfPrincipled", Roughness=0.0, IOR=1.5,
                         renamed={("Transmission Weight", "Transmission"): 1.0})[0]  # fmt: skip


def _grey_veil(bpy):
    return node_material(bpy, "Veil", "ShaderNodeBsdfTransparent", Color=(0.5, 0.5, 0.5))[0]


# the share of the open plane's light under the ball, in Cycles (and so in Whitted)
MATERIALS = {
    "glass_bsdf": (_glass, 0.0),
    "principled_transmission": (_principled_transmission, 0.0),
    "transparent_bsdf": (_grey_veil, 0.25),
}


def _shadow_and_open(image):
    """Mean brightness of the plane well inside the ball's shadow, and well outside it."""
    centre = (np.arange(SIZE) + 0.5) / SIZE * VIEW - VIEW / 2.0
    x, y = np.meshgrid(centre, centre)
    radius = np.hypot(x, y)
    grey = image.mean(axis=-1)
    return grey[radius < 0.8 * RADIUS].mean(), grey[radius > 1.3 * RADIUS].mean()


def _scene(bpy, make_material):
    scene = new_scene(bpy)
    ball = add_ball(bpy, scene, make_material(bpy), location=(0.0, 0.0, 2.0), radius=RADIUS)
    ball.visible_camera = False
    add_light(bpy, scene, "SUN", (0.0, 0.0, 5.0), energy=2.0, angle=0.0)
    scene.whitted.shadow_samples = 1
    # the shadow rule alone: Cycles at diffuse bounces 0 draws no caustic on the plane
    # (test_caustics_in_blender checks Whitted's against closed forms)
    scene.whitted.use_caustics_reflective = scene.whitted.use_caustics_refractive = False
    return scene


@pytest.mark.parametrize("kind", list(MATERIALS))
def test_a_balls_shadow_in_a_sun_is_as_dark_as_in_cycles(bpy_with_whitted, tmp_path, kind):
    bpy = bpy_with_whitted
    make_material, share = MATERIALS[kind]
    scene = _scene(bpy, make_material)
    cycles = render_with(bpy, scene, "CYCLES", tmp_path / "cycles.exr", samples=16)
    whitted = render_with(bpy, scene, "WHITTED", tmp_path / "whitted.exr")
    (c_shadow, c_open), (w_shadow, w_open) = _shadow_and_open(cycles), _shadow_and_open(whitted)
    print(f"{kind}: Cycles {c_shadow:.4f} / {c_open:.4f}, Whitted {w_shadow:.4f} / {w_open:.4f}")
    assert math.isclose(c_shadow / c_open, share, abs_tol=TOLERANCE)  # the premise
    assert math.isclose(w_open, c_open, rel_tol=TOLERANCE)
    assert math.isclose(w_shadow / w_open, c_shadow / c_open, abs_tol=TOLERANCE)


def test_the_classic_rule_lets_light_through_glass_unlike_cycles(bpy_with_whitted, tmp_path):
    """Attenuated: the glass ball (transparency 1) passes all the light, so the plane under
    it is as bright as the open plane."""
    bpy = bpy_with_whitted
    scene = _scene(bpy, _glass)
    scene.whitted.glass_shadows = "ATTENUATED"
    whitted = render_with(bpy, scene, "WHITTED", tmp_path / "whitted.exr")
    shadow, open_plane = _shadow_and_open(whitted)
    assert shadow > 0.9 * open_plane


def test_a_coloured_transparent_balls_shadow_has_cycles_colour(bpy_with_whitted, tmp_path):
    """A Transparent BSDF of colour (1, 0.3, 0.1): Cycles' shadow is that colour squared,
    channel by channel (two crossings), and so is Whitted's; a grey mean would give each
    channel 0.22 of the open plane."""
    bpy = bpy_with_whitted
    colour = (1.0, 0.3, 0.1)
    scene = _scene(bpy, lambda bpy: node_material(bpy, "Red veil", "ShaderNodeBsdfTransparent",
                                                  Color=(*colour, 1.0))[0])  # fmt: skip
    cycles = render_with(bpy, scene, "CYCLES", tmp_path / "cycles.exr", samples=16)
    whitted = render_with(bpy, scene, "WHITTED", tmp_path / "whitted.exr")
    centre = (np.arange(SIZE) + 0.5) / SIZE * VIEW - VIEW / 2.0
    x, y = np.meshgrid(centre, centre)
    radius = np.hypot(x, y)
    for image, name in ((cycles, "Cycles"), (whitted, "Whitted")):
        shadow = image[radius < 0.8 * RADIUS].mean(axis=0)
        open_plane = image[radius > 1.3 * RADIUS].mean(axis=0)
        share = shadow / open_plane
        print(f"{name}: shadow / open plane per channel {np.round(share, 4)}")
        np.testing.assert_allclose(share, np.square(colour), atol=TOLERANCE)
    # and nothing warns of a grey shadow (the export once noted "used: its mean")
    export = sys.modules["whitted.export"]
    _, _, warnings = export.convert(bpy.context.evaluated_depsgraph_get())
    assert not any("Red veil" in warning for warning in warnings), warnings
