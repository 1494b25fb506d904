"""Beer-Lambert absorption inside glass (core.kernels.absorption: Blender's Volume Absorption,
glTF's attenuation) against closed forms computed here:

- a ball of index 1 (nothing bends, nothing reflects) in a white World: each pixel is
  exp(-sigma L) per channel, L the chord its ray crosses, 2 sqrt(1 - x^2 - z^2);
- a glass ball of index 1.5 in a white World: every internal chord of a ray in a sphere has
  the same length L = 2 cos(theta_t) and meets the surface at the same angle, so summing
  every internal reflection the pixel is F + (1 - F)^2 e^(-sigma L) / (1 - F e^(-sigma L));
- caustic photons through an absorbing slab under a sun overhead: the floor below it is the
  clear slab's times e^(-sigma h) (1 - F^2) / (1 - F^2 e^(-2 sigma h)), h its thickness.
"""

import math

import numpy as np
import pytest

from core import (
    Box,
    Camera,
    Environment,
    Material,
    RenderSettings,
    Scene,
    SceneError,
    SunLight,
    render,
)
from core.compile import compile_scene
from core.compile.features import expected_features, used_features
from tests.core.test_caustics import _fresnel, _placed
from tests.core.test_environment import ball, hits, look_at_ball

SIZE = 24
SIGMA = (0.3, 1.1, 2.6)  # per unit length: red passes, blue is taken


def _ball_seen(material, max_depth=2):
    scene = Scene(look_at_ball(), [ball(material)], environment=Environment(colour=(1.0,) * 3))
    settings = RenderSettings(SIZE, SIZE, pixel_samples=1, max_depth=max_depth)
    return render(scene, settings).image[..., :3].astype(float)


def test_a_ball_of_index_one_keeps_exp_of_minus_sigma_times_its_chord():
    glass = Material(diffuse=(0.0, 0.0, 0.0), transparency=1.0, inner_ior=1.0, absorption=SIGMA)
    seen = _ball_seen(glass)
    points, inside = hits(SIZE)
    chord = -2.0 * points[..., 1][inside]
    expected = np.exp(-np.outer(chord, SIGMA))
    np.testing.assert_allclose(seen[inside], expected, atol=2e-6)  # float32 pixels
    assert (seen[~inside] == 1.0).all()  # the World beside it, untouched


def test_a_glass_ball_sums_its_internal_reflections_each_absorbed_over_its_chord():
    glass = Material(diffuse=(0.0, 0.0, 0.0), transparency=1.0, inner_ior=1.5, absorption=SIGMA)
    seen = _ball_seen(glass, max_depth=24)
    points, inside = hits(SIZE)
    cos_i = -points[..., 1][inside]
    f, cos_t = _fresnel(cos_i, 1.0, 1.5)
    kept = np.exp(-np.outer(2.0 * cos_t, SIGMA))
    expected = f[:, None] + (1.0 - f[:, None]) ** 2 * kept / (1.0 - f[:, None] * kept)
    # rays fainter than the integrator's MIN_WEIGHT (1e-6) are dropped: near the rim, where
    # F is large, a few of them
    np.testing.assert_allclose(seen[inside], expected, atol=2e-5)
    clear = _ball_seen(Material(diffuse=(0.0,) * 3, transparency=1.0, inner_ior=1.5), 24)
    assert (seen[inside] < clear[inside] - 1e-3).all(axis=0).any()  # the premise: it takes


def _floor_under_slab(absorption, photons=40_000):
    """The floor's RGB under a glass slab 0.2 thick (a Box spans -1..1; index 1.5) lit by a
    sun overhead, its light brought only by caustic photons (glass shadows blocked, as in
    Cycles)."""
    glass = Material(diffuse=(0.0,) * 3, transparency=1.0, inner_ior=1.5, absorption=absorption)
    slab = Box("Slab", glass, _placed(z=1.0, size=(3.0, 3.0, 0.1)))
    slab.seen_by_camera = False
    floor = Box("Floor", Material(diffuse=(1.0, 1.0, 1.0)), _placed(z=-0.5, size=(30, 30, 0.5)))
    camera = Camera(eye=(0.0, 0.0, 10.0), view=(0.0, 0.0, -1.0), up=(0.0, 1.0, 0.0),
                    projection="orthographic", ortho_height=2.0)  # fmt: skip
    sun = SunLight(name="Sun", direction=(0.0, 0.0, -1.0), irradiance=(1.0, 1.0, 1.0))
    settings = RenderSettings(16, 16, pixel_samples=1, glass_shadows="blocked", max_depth=8,
                              caustics=("refractive",), caustic_photons=photons)  # fmt: skip
    scene = Scene(shapes=[floor, slab], lights=[sun], camera=camera)
    return render(scene, settings).image[..., :3].astype(float), scene, settings


def test_photons_through_an_absorbing_slab_lose_exp_of_minus_sigma_times_its_thickness():
    """The same photons take the same paths in both (absorption changes their power, not
    their choices), so the ratio is the closed form to the share of photons reflected
    inside (F^2, 0.2%)."""
    absorbing, scene, settings = _floor_under_slab(SIGMA)
    clear, _, _ = _floor_under_slab((0.0, 0.0, 0.0))
    assert clear.min() > 0.15  # the premise: lit through the slab (the open floor: 1/pi)
    h, f = 0.2, ((1.5 - 1.0) / 2.5) ** 2
    sigma = np.asarray(SIGMA)
    expected = np.exp(-sigma * h) * (1.0 - f * f) / (1.0 - f * f * np.exp(-2.0 * sigma * h))
    ratio = absorbing.reshape(-1, 3).sum(axis=0) / clear.reshape(-1, 3).sum(axis=0)
    # each photon carries the same power whatever its path (Russian roulette), so the ratio
    # is the closed form but for how many of the ~4,000 photons seen reflected inside
    np.testing.assert_allclose(ratio, expected, rtol=2e-3)
    packed = compile_scene(scene, settings).packed
    assert "absorption" in used_features(packed)
    assert "absorption" in expected_features(scene, settings)


def test_shadow_rays_that_cross_an_absorbing_glass_are_warned_of():
    glass = Material(name="Tinted", transparency=1.0, inner_ior=1.5, absorption=SIGMA)
    scene = Scene(look_at_ball(), [ball(glass)])
    attenuated = compile_scene(scene, RenderSettings(8, 8, glass_shadows="attenuated"))
    assert any("'Tinted'" in w and "not absorbed" in w for w in attenuated.warnings)
    blocked = compile_scene(scene, RenderSettings(8, 8, glass_shadows="blocked"))
    assert not any("absorbed" in w for w in blocked.warnings)


def test_a_scene_without_absorption_compiles_none():
    scene = Scene(look_at_ball(), [ball(Material(transparency=1.0, inner_ior=1.5))])
    settings = RenderSettings(8, 8)
    assert "absorption" not in used_features(compile_scene(scene, settings).packed)
    assert "absorption" not in expected_features(scene, settings)


@pytest.mark.parametrize("value", [(-0.1, 0.0, 0.0), (math.nan, 0.0, 0.0)])
def test_a_negative_absorption_is_refused_by_name(value):
    with pytest.raises(SceneError, match="absorption"):
        render(Scene(look_at_ball(), [ball(Material(absorption=value))]), RenderSettings(4, 4))
