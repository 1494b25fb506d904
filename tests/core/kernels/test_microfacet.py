"""The rough lobes' glint (core.kernels.microfacet), checked against what defines it: its
albedo table against an independent integration over light directions, the light a
lobe reflects in all (a white Multiscatter GGX lobe keeps it all, a single-scattering one
keeps the table's E), Helmholtz reciprocity, and a rough layer's reflectance becoming the
exact Fresnel as it turns smooth."""

import math

import numba
import numpy as np
import pytest

from core.kernels.fresnel import fresnel_dielectric
from core.kernels.ggx_albedo_table import DIELECTRIC_SIZE, TABLE_SIZE
from core.kernels.microfacet import (
    E_TABLE,
    F_MEAN,
    Gloss,
    ggx_albedo,
    ggx_albedo_average,
    gloss_lit,
    multiscatter_fresnel,
    rough_coat_albedo,
)

WHITE, BLACK = (1.0, 1.0, 1.0), (0.0, 0.0, 0.0)


def _ggx_albedo_over_lights(roughness, mu, n=1500):
    """E(r, mu) = int D G2 / (4 mu) over light directions, by the midpoint rule in
    (cos theta, phi): numpy, independent of the table's visible-normal integration."""
    alpha2 = (roughness * roughness) ** 2
    c = (np.arange(n) + 0.5) / n
    phi = (np.arange(n) + 0.5) / n * np.pi  # the half phi > 0: the lobe is symmetric
    cos, p = np.meshgrid(c, phi, indexing="ij")
    sin = np.sqrt(1.0 - cos * cos)
    light = np.stack([sin * np.cos(p), sin * np.sin(p), cos], -1)
    view = np.array([math.sqrt(1.0 - mu * mu), 0.0, mu])
    h = light + view
    h /= np.linalg.norm(h, axis=-1)[..., None]
    t = 1.0 + (alpha2 - 1.0) * h[..., 2] ** 2
    d = alpha2 / (np.pi * t * t)

    def lam(x):
        return 0.5 * (np.sqrt(1.0 + alpha2 * (1.0 / (x * x) - 1.0)) - 1.0)

    g2 = 1.0 / (1.0 + lam(mu) + lam(cos))
    return 2.0 * (d * g2 / (4.0 * mu)).sum() / n * (np.pi / n)


@pytest.mark.parametrize("roughness, mu", [(0.5, 0.5), (0.5, 1.0), (0.75, 0.25), (1.0, 1.0),
                                           (1.0, 0.125), (0.625, 0.75)])  # fmt: skip
def test_the_albedo_table_agrees_with_an_integration_over_light_directions(roughness, mu):
    i, j = round(roughness * (TABLE_SIZE - 1)), round(mu * (TABLE_SIZE - 1))
    assert E_TABLE[i, j] == pytest.approx(_ggx_albedo_over_lights(roughness, mu), abs=2e-3)


@numba.njit(cache=False)
def _reflected_in_all(gloss, mu, n):
    """int gloss_lit / pi over light directions (what the emitters' pi takes back), by the
    midpoint rule in (cos theta, phi)."""
    view = (math.sqrt(1.0 - mu * mu), 0.0, mu)
    normal = (0.0, 0.0, 1.0)
    total = np.zeros(3)
    for a in range(n):
        cos = (a + 0.5) / n
        sin = math.sqrt(1.0 - cos * cos)
        for b in range(2 * n):
            phi = (b + 0.5) / (2 * n) * 2.0 * math.pi
            light = (sin * math.cos(phi), sin * math.sin(phi), cos)
            f = gloss_lit(gloss, normal, view, light)
            for c in range(3):
                total[c] += f[c]
    return total / math.pi * (1.0 / n) * (math.pi / n)


def _white(roughness, multiscatter):
    ms = WHITE if multiscatter else BLACK
    fms = multiscatter_fresnel(1.0, ggx_albedo_average(roughness))
    assert fms == pytest.approx(1.0)
    return Gloss(roughness * roughness, False, WHITE, WHITE, ms, ms, 0.0, 1.5, 0.0, WHITE, BLACK)


@pytest.mark.parametrize("roughness", [0.4, 0.7, 1.0])
@pytest.mark.parametrize("mu", [0.3, 0.8])
def test_a_white_multiscatter_lobe_reflects_all_the_light_and_a_single_one_its_albedo(
    roughness, mu
):
    single = _reflected_in_all(_white(roughness, False), mu, 600)
    multiple = _reflected_in_all(_white(roughness, True), mu, 600)
    assert single[0] == pytest.approx(ggx_albedo(roughness, mu), abs=5e-3)
    assert multiple[0] == pytest.approx(1.0, abs=1e-2)


@pytest.mark.parametrize("beckmann", [False, True])
def test_a_glint_is_the_same_with_light_and_view_exchanged(beckmann):
    """f(v, l) = f(l, v): gloss_lit / cos(l) is symmetric, for GGX's and Beckmann's lobes,
    with Fresnel and a coat."""
    rng = np.random.default_rng(61)
    gloss = Gloss(0.3, beckmann, (0.9, 0.6, 0.2), WHITE, BLACK, BLACK, 0.5, 1.5, 0.0, WHITE, BLACK)
    normal = (0.0, 0.0, 1.0)
    for _ in range(200):
        v, lt = (tuple(x / np.linalg.norm(x)) for x in np.abs(rng.normal(size=(2, 3))))
        forward = np.array(gloss_lit(gloss, normal, v, lt)) / lt[2]
        back = np.array(gloss_lit(gloss, normal, lt, v)) / v[2]
        np.testing.assert_allclose(forward, back, rtol=1e-9, atol=1e-12)


@pytest.mark.parametrize("ior", [1.33, 1.5, 2.4])
def test_a_rough_layer_turning_smooth_reflects_the_exact_fresnel(ior):
    """At roughness 0 the dielectric table's mean Fresnel is the exact Fresnel of the view
    (the lobe is the mirror direction alone), and rough_coat_albedo with it."""
    gloss = Gloss(0.0, False, BLACK, BLACK, BLACK, BLACK, 1.0, ior, 0.0, WHITE, BLACK)
    for cos in (0.25, 0.5, 0.75, 1.0):
        exact, _ = fresnel_dielectric(cos, 1.0, ior)
        assert rough_coat_albedo(gloss, 0.0, cos) == pytest.approx(exact, abs=4e-3)
    assert F_MEAN.shape == (DIELECTRIC_SIZE,) * 3
