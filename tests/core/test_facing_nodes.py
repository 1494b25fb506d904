"""Blender's Fresnel and Layer Weight nodes (core.kernels.facing_values), run per hit,
against closed forms computed here: a ball whose Emission colour is the node's output, seen
orthographically (each pixel's |I . N| known exactly), shows at each pixel

- Fresnel: the unpolarised dielectric reflectance from Fresnel's s and p amplitudes
  (tests/core/test_node_material_terms._fresnel, not the kernel's formula), at IOR seen
  from outside and, from a camera inside the ball (the ray meets its back), at 1 / IOR:
  1 past the critical angle;
- Layer Weight: Fresnel at 1 / (1 - Blend) and Facing 1 - |I . N|^p, p as Blender's manual
  gives it from Blend;
- a Normal input that is linked takes the place of the surface's.

And the library glass (a Mix Shader of Refraction and Glossy by a Fresnel node of the same
IOR) renders as the Glass BSDF, whose Fresnel test_node_material_terms checks against the
closed form, inside reflections and all; and under a sun it casts the ball lens's caustic
as the exact tracer of tests/core/test_caustics.py draws it; a veil mixed by Facing
shadows by each shadow ray's own angle. Side by side with Cycles:
tests/blender/test_cycles_textures.py and test_cycles_materials.py."""

import math

import numpy as np
import pytest

from core import Camera, Environment, Link, Material, RenderSettings, Scene, ShaderNode, render
from core.model.materials import Texture
from tests.core.test_caustics import N, ball_lens_region
from tests.core.test_coloured_shadows import LIGHTS, _floor_under
from tests.core.test_environment import ball, hits, look_at_ball
from tests.core.test_node_material_terms import _fresnel

pytestmark = pytest.mark.filterwarnings("ignore:invalid value:RuntimeWarning")  # the rim's 0/0
SIZE = 24


def _glowing(value, camera=None):
    """The picture of a unit ball glowing with `value` (a Link to a number) as its colour."""
    glow = ShaderNode("emission", {"Color": value, "Strength": 1.0})
    scene = Scene(camera or look_at_ball(), [ball(Material(surface=glow))],
                  environment=Environment(colour=(0.0, 0.0, 0.0)))  # fmt: skip
    settings = RenderSettings(SIZE, SIZE, pixel_samples=1, max_depth=2)
    image = render(scene, settings).image[..., :3].astype(float)
    assert np.ptp(image, axis=-1).max() < 1e-6  # grey: the number, repeated
    return image[..., 0]


def _cosines():
    points, inside = hits(SIZE)
    return -points[..., 1], inside  # |I . N| from -Y: the normal's y


@pytest.mark.parametrize("ior", [1.45, 2.4, 0.8])
def test_fresnel_seen_from_outside_is_the_dielectric_reflectance_at_its_ior(ior):
    seen = _glowing(Link(ShaderNode("fresnel", {"IOR": ior}), "Fac"))
    cos_i, inside = _cosines()
    np.testing.assert_allclose(seen[inside], _fresnel(cos_i, 1.0, ior)[inside], atol=2e-6)
    assert np.all(seen[~inside] == 0.0)


def test_fresnel_on_the_balls_inside_is_at_one_over_its_ior_and_total_past_critical():
    """The camera at (0, 0.5, 0) inside the ball looking along +Y: each ray meets the back
    of the surface at y = sqrt(1 - r^2) where r^2 < 0.75, at cos = y."""
    inside_view = Camera(eye=(0.0, 0.5, 0.0), view=(0.0, 1.0, 0.0), up=(0.0, 0.0, 1.0),
                         projection="orthographic", ortho_height=2.0)  # fmt: skip
    seen = _glowing(Link(ShaderNode("fresnel", {"IOR": 1.5}), "Fac"), inside_view)
    points, _ = hits(SIZE)
    r2 = points[..., 0] ** 2 + points[..., 2] ** 2
    met = r2 < 0.7  # clear of the rim where the rays start outside the ball
    cos_i = np.sqrt(np.clip(1.0 - r2, 0.0, None))
    want = _fresnel(cos_i, 1.5, 1.0)
    np.testing.assert_allclose(seen[met], want[met], atol=2e-6)
    assert np.any(want[met] == 1.0) and np.any(want[met] < 0.1)  # both sides of critical


@pytest.mark.parametrize("blend", [0.0, 0.2, 0.5, 0.8, 1.0])
def test_layer_weight_is_fresnel_at_one_over_one_minus_blend_and_a_power_of_facing(blend):
    node = ShaderNode("layer_weight", {"Blend": blend})
    fresnel, facing = _glowing(Link(node, "Fresnel")), _glowing(Link(node, "Facing"))
    cos_i, inside = _cosines()
    eta = 1.0 / max(1.0 - blend, 1e-5)
    np.testing.assert_allclose(fresnel[inside], _fresnel(cos_i, 1.0, eta)[inside], atol=2e-6)
    # the manual: Blend 0.5 is 1 - |I.N|; below it the power falls to 0 (Facing 0), above it
    # rises without bound (Facing 1 but where I.N = 1)
    b = min(blend, 1.0 - 1e-5)
    power = 2.0 * b if b < 0.5 else 0.5 / (1.0 - b)
    np.testing.assert_allclose(facing[inside], (1.0 - cos_i**power)[inside], atol=2e-6)


def test_a_linked_normal_takes_the_place_of_the_surfaces():
    """Fed the view's own axis as its Normal, Fresnel is its head-on value at every pixel."""
    axis = ShaderNode("combine", {"X": 0.0, "Y": -1.0, "Z": 0.0})
    seen = _glowing(Link(ShaderNode("fresnel", {"IOR": 1.5, "Normal": Link(axis, "Vector")}),
                         "Fac"))  # fmt: skip
    _, inside = _cosines()
    np.testing.assert_allclose(seen[inside], 0.04, atol=2e-6)  # ((1.5 - 1) / 2.5)^2


def _sky():
    rng = np.random.default_rng(8)
    image = Texture(pixels=rng.uniform(0.0, 2.0, (8, 16, 3)), srgb=False)
    return Environment(colour=(1.0, 1.0, 1.0), image=image, interpolation="closest")


def _library_glass(ior):
    """Refraction and Glossy mixed by a Fresnel node of the same IOR."""
    fresnel = ShaderNode("fresnel", {"IOR": ior})
    refraction = ShaderNode("refraction", {"IOR": ior, "Color": (1.0, 1.0, 1.0)})
    mirror = ShaderNode("glossy", {"Color": (1.0, 1.0, 1.0), "Roughness": 0.0})
    return ShaderNode("mix_shader", {"Fac": Link(fresnel, "Fac"), "Shader A": Link(refraction),
                                     "Shader B": Link(mirror)})  # fmt: skip


def test_the_library_glass_mixed_by_fresnel_renders_as_the_glass_bsdf():
    mixed = _library_glass(1.5)
    glass = ShaderNode("glass", {"IOR": 1.5, "Color": (1.0, 1.0, 1.0), "Roughness": 0.0})
    settings = RenderSettings(SIZE, SIZE, pixel_samples=1, max_depth=10)
    pictures = [
        render(
            Scene(look_at_ball(), [ball(Material(surface=surface))], environment=_sky()), settings
        )
        .image[..., :3]
        .astype(float)  # fmt: skip
        for surface in (mixed, glass)
    ]
    _, inside = _cosines()
    assert np.ptp(pictures[1][inside]) > 0.5  # the sky shows through and in it
    np.testing.assert_allclose(pictures[0], pictures[1], rtol=1e-4, atol=1e-5)


def test_the_library_glass_casts_the_ball_lenss_caustic():
    """Photons meet the Fresnel node too (at their own direction and side): the library
    glass ball's light on the floor about its shadow is the exact tracer's."""
    measured, expected, bare = ball_lens_region(_library_glass(N), "Fresnel glass")
    print(f"library glass: region {measured:.4f} against {expected:.4f}")
    assert math.isclose(measured, expected, rel_tol=0.03)
    assert measured > bare + 0.5 * (expected - bare)  # the premise: not the bare shadow


def test_a_veil_mixed_by_facing_shadows_by_the_shadow_rays_own_angle():
    """A ball of Transparent (white) mixed into black Diffuse by Layer Weight's Facing (Blend
    0.5: 1 - |I . N|): under a sun straight down, each shadow ray crosses the ball where
    |I . N| = sqrt(1 - r^2), twice, so the floor gets (1 - r^2) of the open floor's light:
    the shadow crossings read their own ray's direction."""
    facing = ShaderNode("layer_weight", {"Blend": 0.5})
    clear, black = ShaderNode("transparent", {}), ShaderNode("diffuse", {"Color": (0.0,) * 3})
    veil = ShaderNode("mix_shader", {"Fac": Link(facing, "Facing"), "Shader A": Link(clear),
                                     "Shader B": Link(black)})  # fmt: skip
    out, _, radius = _floor_under(Material(name="Veil", surface=veil), LIGHTS["sun"])
    image = out.image[..., :3].astype(float)
    lit = image[radius > 1.1].mean(axis=0)
    under = radius < 0.95
    expected = lit[None, :] * (1.0 - radius[under] ** 2)[:, None]
    np.testing.assert_allclose(image[under], expected, rtol=1e-5, atol=1e-6)
