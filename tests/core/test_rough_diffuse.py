"""Rough diffuse reflection (core.kernels.rough_diffuse) against what the test integrates
itself: FON's albedo in closed form against the hemisphere summed numerically; EON's
furnace (at albedo 1 its two lobes reflect all the light falling from any direction, and
a white ball under a uniform World is as bright as the World); and a rough ball under a
sharp sun, each pixel against the model's formula with FON's albedo integrated here. Side
by side with Cycles, in 4.2 (FON) and from 4.5 (EON): tests/blender/test_cycles_rough_diffuse.py."""

import math

import numpy as np
import pytest

from core import Environment, Material, RenderSettings, Scene, Sphere, SunLight, render
from core.kernels.rough_diffuse import ROUGH_EON, ROUGH_FON, fon_g, rough_response
from tests.core.test_environment import hits, look_at_ball

SIZE = 16
C = 0.5 - 2.0 / (3.0 * math.pi)


def _hemisphere(n=240):
    """Directions over the upper hemisphere about +z and their solid angles (midpoints)."""
    theta = (np.arange(n) + 0.5) / n * (math.pi / 2)
    phi = (np.arange(2 * n) + 0.5) / (2 * n) * (2 * math.pi)
    t, p = np.meshgrid(theta, phi, indexing="ij")
    dirs = np.stack([np.sin(t) * np.cos(p), np.sin(t) * np.sin(p), np.cos(t)], axis=-1)
    return dirs.reshape(-1, 3), (np.sin(t) * (math.pi / 2 / n) * (math.pi / n)).ravel()


DIRS, SOLID = _hemisphere()


def _view(mu):
    return np.array([math.sqrt(1.0 - mu * mu), 0.0, mu])


def _fon_ratio(mu_l, mu_v, l_dot_v, sigma):
    """FON's pi f / rho, written out here."""
    a = 1.0 / (1.0 + C * sigma)
    s = l_dot_v - mu_l * mu_v
    t = np.where(s > 0, np.maximum(np.maximum(mu_l, mu_v), 1e-12), 1.0)
    return a + sigma * a * s / t


def _fon_albedo(mu_v, sigma):
    v = _view(mu_v)
    ratio = _fon_ratio(DIRS[:, 2], mu_v, DIRS @ v, sigma)
    return float((ratio * DIRS[:, 2] * SOLID).sum() / math.pi)


@pytest.mark.parametrize("mu", [0.02, 0.3, 0.7, 0.999])
def test_fons_albedo_in_closed_form_is_the_hemisphere_summed(mu):
    a = 1.0 / (1.0 + C)
    closed = a + a * fon_g(mu) / math.pi
    assert closed == pytest.approx(_fon_albedo(mu, 1.0), abs=2e-5)


def _albedo_of_kernel(mu_v, sigma, model, kd=1.0):
    v, n = _view(mu_v), (0.0, 0.0, 1.0)
    total = 0.0
    for d, w in zip(DIRS[::7], SOLID[::7] * 7, strict=True):
        total += rough_response((kd,) * 3, sigma, model, n, tuple(d), tuple(v))[0] * d[2] * w
    return total / math.pi


@pytest.mark.parametrize("mu", [0.1, 0.5, 0.95])
@pytest.mark.parametrize("sigma", [0.4, 1.0])
def test_eon_at_albedo_1_reflects_all_the_light_and_fon_its_albedo(mu, sigma):
    assert _albedo_of_kernel(mu, sigma, ROUGH_EON) == pytest.approx(1.0, abs=2e-3)
    assert _albedo_of_kernel(mu, sigma, ROUGH_FON) == pytest.approx(_fon_albedo(mu, sigma),
                                                                    abs=2e-3)  # fmt: skip


def _ball(kd, sigma):
    return Sphere("Ball", Material(diffuse=kd, diffuse_roughness=sigma), np.eye(4))


def test_a_white_rough_ball_in_a_white_world_is_white():
    """The furnace: EON loses no light, whatever the roughness (FON would darken the ball
    towards its rim, to its albedo: 0.95 to 0.80 at roughness 1)."""
    scene = Scene(look_at_ball(), [_ball((1.0, 1.0, 1.0), 1.0)],
                  environment=Environment(colour=(1.0, 1.0, 1.0)))  # fmt: skip
    settings = RenderSettings(SIZE, SIZE, pixel_samples=1, environment_samples=1024)
    seen = render(scene, settings).image[..., :3].astype(float)
    _, inside = hits(SIZE)
    assert seen[inside].mean() == pytest.approx(1.0, abs=3e-3)
    assert np.abs(seen[inside] - 1.0).max() < 0.06


@pytest.mark.parametrize("model", ["FON", "EON"])
def test_a_rough_ball_under_a_sharp_sun_follows_the_model_pixel_by_pixel(model):
    """A ball of colour (0.8, 0.5, 0.2), roughness 0.7, lit from the upper right: each
    pixel is the sun's irradiance times cos and the model's f, worked out here (EON's
    multiple-scattering lobe weighted by the colour once more, as Cycles weights it)."""
    kd, sigma = np.array((0.8, 0.5, 0.2)), 0.7
    to_sun = np.array((0.5, -0.4, 0.6))
    to_sun /= np.linalg.norm(to_sun)
    sun = SunLight(direction=tuple(-to_sun), irradiance=(2.0,) * 3, angle=0.0)
    scene = Scene(look_at_ball(), [_ball(tuple(kd), sigma)], [sun])
    settings = RenderSettings(SIZE, SIZE, pixel_samples=1, rough_diffuse=model)
    seen = render(scene, settings).image[..., :3].astype(float)
    points, inside = hits(SIZE)
    to_camera = np.array((0.0, -1.0, 0.0))
    mu_l, mu_v = points @ to_sun, points @ to_camera
    ratio = _fon_ratio(np.clip(mu_l, 0, None), mu_v, to_sun @ to_camera, sigma)[..., None] * kd
    if model == "EON":
        a = 1.0 / (1.0 + C * sigma)
        mus = np.linspace(0.0, 1.0, 41)
        albedo = np.array([_fon_albedo(m, sigma) for m in mus])
        weighted = albedo * mus  # (the trapezoid rule: np.trapz is gone from numpy 2)
        mean = float(np.sum((weighted[1:] + weighted[:-1]) * np.diff(mus)))
        assert mean == pytest.approx(a + sigma * a * (2 / 3 - 28 / (15 * math.pi)), abs=2e-3)
        lost_l = 1.0 - np.interp(np.clip(mu_l, 0, 1), mus, albedo)
        lost_v = 1.0 - np.interp(np.clip(mu_v, 0, 1), mus, albedo)
        rho_ms = kd**2 * mean / (1.0 - kd * (1.0 - mean))
        ratio += kd * rho_ms * (lost_l * lost_v / (1.0 - mean))[..., None]
    expected = 2.0 * np.clip(mu_l, 0, None)[..., None] * ratio / math.pi
    lit = inside & (mu_l > 0.05) & (mu_v > 0.05)
    assert lit.mean() > 0.3
    np.testing.assert_allclose(seen[lit], expected[lit], rtol=3e-3, atol=1e-4)
    assert np.abs(seen[lit] - 2.0 * mu_l[lit, None] * kd / math.pi).max() > 0.02  # not Lambert


def test_an_unknown_model_or_roughness_is_refused_by_name():
    from core import SceneError

    with pytest.raises(SceneError, match="rough_diffuse"):
        RenderSettings(4, 4, rough_diffuse="Oren-Nayar").validate()
    with pytest.raises(SceneError, match="diffuse_roughness"):
        Material(diffuse_roughness=1.5).validate("a test")
