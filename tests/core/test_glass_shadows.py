"""The glass-shadow rule (RenderSettings.glass_shadows), against closed forms: under
"attenuated" (the report's rule) a shadow ray passes each crossing of a refracting surface
dimmed by its transparency; under "blocked" (Blender scenes' default, as physics and Cycles
have it) a refracting surface stops it. What passes a surface straight (Transparent BSDF,
Alpha) lets the same light through under both; constant and per-hit (programmed) materials
follow the same rule. A floor under a glass ball in a sun shows it: its shadow is tau^2 of
the open floor, or black."""

import math

import numpy as np
import pytest

from core import (
    Camera,
    Material,
    RenderSettings,
    Scene,
    SceneError,
    ShaderNode,
    Sphere,
    SunLight,
    render,
)
from core.compile import compile_scene, with_frame
from core.kernels.shadow_log import SHADOW_VARIES
from tests.core.test_shadows_through_node_materials import x_mix_material
from tests.support.probe import light_by_full_rule

RULES = ("attenuated", "blocked")
DOWN_Z = ((0.0, 0.0, -3.0), (0.0, 0.0, 1.0), 6.0)  # a shadow ray through the unit ball's centre


def _packed(rule, *shapes, lights=(), camera=None):
    scene = Scene(shapes=list(shapes), lights=list(lights))
    if camera is not None:
        scene.camera = camera
    return compile_scene(scene, RenderSettings(8, 8, pixel_samples=1, glass_shadows=rule))


def _ball(material):
    return Sphere("Ball", material, np.eye(4))


def _principled(**inputs):
    return Material(name="Principled", surface=ShaderNode("principled", inputs))


@pytest.mark.parametrize("rule", RULES)
def test_a_constant_glass_passes_its_transparency_squared_or_nothing(rule):
    packed = _packed(rule, _ball(Material(transparency=0.8, reflectivity=0.1))).packed
    expected = 0.8**2 if rule == "attenuated" else 0.0
    assert math.isclose(light_by_full_rule(packed, *DOWN_Z), expected, abs_tol=1e-12)


@pytest.mark.parametrize("rule", RULES)
@pytest.mark.parametrize(
    "material",
    [
        _principled(Transmission=1.0, Roughness=0.0),
        Material(name="Glass", surface=ShaderNode("glass", {"IOR": 1.5})),
        Material(name="Refraction", surface=ShaderNode("refraction", {"IOR": 1.5})),
    ],
    ids=["principled_transmission", "glass_bsdf", "refraction_bsdf"],
)
def test_blender_glass_materials_follow_the_rule(rule, material):
    packed = _packed(rule, _ball(material)).packed
    passed = light_by_full_rule(packed, *DOWN_Z)
    if rule == "blocked":
        assert passed == 0.0
    else:
        assert passed > 0.9  # transparency 1 at both crossings (less any tint)


@pytest.mark.parametrize("rule", RULES)
def test_a_transparent_bsdf_and_alpha_pass_light_under_either_rule(rule):
    transparent = Material(name="Veil", surface=ShaderNode("transparent", {"Color": (0.5,) * 3}))
    packed = _packed(rule, _ball(transparent)).packed
    assert math.isclose(light_by_full_rule(packed, *DOWN_Z), 0.25, rel_tol=1e-9)
    alpha = _principled(Alpha=0.3)
    packed = _packed(rule, _ball(alpha)).packed
    assert math.isclose(light_by_full_rule(packed, *DOWN_Z), 0.7**2, rel_tol=1e-9)


@pytest.mark.parametrize("rule", RULES)
def test_per_hit_materials_follow_the_rule_at_each_crossing(rule):
    """A diffuse/glass mix varying over the ball: under "attenuated" each crossing passes
    its glass share (0.5 + 0.4 X); under "blocked" the material can pass no light at all,
    so no program runs for its shadows. A diffuse/transparent mix passes its share either
    way."""
    x0 = 0.45
    ray = ((x0, 0.0, -3.0), (0.0, 0.0, 1.0), 6.0)
    glass = _packed(rule, _ball(x_mix_material(ShaderNode("glass", {"IOR": 1.5})))).packed
    transparent = _packed(rule, _ball(x_mix_material(ShaderNode("transparent")))).packed
    share = (0.5 + 0.4 * x0) ** 2
    assert transparent.geometry.shape_transparency[0] == SHADOW_VARIES
    assert math.isclose(light_by_full_rule(transparent, *ray), share, rel_tol=1e-9)
    if rule == "attenuated":
        assert glass.geometry.shape_transparency[0] == SHADOW_VARIES
        assert math.isclose(light_by_full_rule(glass, *ray), share, rel_tol=1e-9)
    else:
        assert glass.geometry.shape_transparency[0] == 0.0
        assert light_by_full_rule(glass, *ray) == 0.0


def _floor_under_ball(rule, transparency):
    """A diffuse floor (z = -2) seen from straight above, a ball of the given transparency
    at the origin, a sun straight down: ([floor pixels inside the ball's shadow], [outside])."""
    floor = Sphere("Floor", Material(diffuse=(0.8, 0.8, 0.8)),
                   _lowered(-2.0) @ np.diag([50.0, 50.0, 1e-3, 1.0]))  # fmt: skip
    ball = _ball(Material(diffuse=(0.0, 0.0, 0.0), transparency=transparency))
    ball.seen_by_camera = False
    sun = SunLight(name="Sun", direction=(0.0, 0.0, -1.0), irradiance=(3.0, 3.0, 3.0))
    size = 32
    camera = Camera(eye=(0.0, 0.0, 10.0), view=(0.0, 0.0, -1.0), up=(0.0, 1.0, 0.0),
                    projection="orthographic", ortho_height=4.0)  # fmt: skip
    scene = Scene(shapes=[floor, ball], lights=[sun], camera=camera)
    settings = RenderSettings(size, size, pixel_samples=1, glass_shadows=rule, max_depth=0)
    image = render(scene, settings).image[..., :3].mean(axis=-1)
    centre = (np.arange(size) + 0.5) / size * 4.0 - 2.0
    x, y = np.meshgrid(centre, centre)
    radius = np.hypot(x, y)
    return image[radius < 0.9], image[radius > 1.1]


def _lowered(z):
    m = np.eye(4)
    m[2, 3] = z
    return m


@pytest.mark.parametrize("rule", RULES)
def test_a_glass_balls_shadow_in_a_sun_is_tau_squared_or_black(rule):
    inside, outside = _floor_under_ball(rule, transparency=0.7)
    lit = outside.mean()
    assert lit > 0.1 and np.ptp(outside) < 1e-6 * lit  # the open floor, evenly lit
    expected = 0.7**2 * lit if rule == "attenuated" else 0.0
    np.testing.assert_allclose(inside, expected, rtol=1e-6, atol=1e-9)  # a float32 image


def test_the_report_rule_is_the_default_and_a_bad_rule_is_refused():
    assert RenderSettings().glass_shadows == "attenuated"
    with pytest.raises(SceneError, match="glass_shadows"):
        RenderSettings(glass_shadows="opaque").validate()


def test_a_new_frame_keeps_the_compiled_rule():
    """The shapes' shadow shares are packed under the compiled rule: reframing under the
    other would mix the two, so it is refused."""
    compiled = _packed("blocked", _ball(Material(transparency=0.5)))
    scene = Scene(shapes=[_ball(Material(transparency=0.5))])
    with_frame(compiled, scene, RenderSettings(16, 16, glass_shadows="blocked"))
    with pytest.raises(ValueError, match="glass_shadows"):
        with_frame(compiled, scene, RenderSettings(16, 16, glass_shadows="attenuated"))
