"""Rough mirrors and glass (core.kernels.glossy): the sampled microfacet normals against
GGX's closed forms, and what glossy samples change in a picture."""

import math

import numpy as np
import pytest

from core.kernels.glossy import visible_normal

N = (0.0, 0.0, 1.0)


def _normals(to_viewer, alpha, count, seed, n=N):
    rng = np.random.default_rng(seed)
    u = rng.random((count, 2))
    return np.array([visible_normal(to_viewer, n, alpha, a, b) for a, b in u])


@pytest.mark.parametrize("alpha", [0.05, 0.3, 0.8])
def test_seen_head_on_the_normals_follow_ggx(alpha):
    """Viewed along the normal every microfacet is visible and the visible distribution is
    D(m) cos(theta_m), whose tan^2 theta_m has the CDF t / (alpha^2 + t)."""
    m = _normals(N, alpha, 20000, seed=1)
    tan2 = (m[:, 0] ** 2 + m[:, 1] ** 2) / m[:, 2] ** 2
    t = np.sort(tan2)
    empirical = np.arange(1, t.size + 1) / t.size
    assert np.abs(empirical - t / (alpha**2 + t)).max() < 0.012  # Kolmogorov, 20000 samples
    np.testing.assert_allclose(np.linalg.norm(m, axis=1), 1.0, atol=1e-12)


def _smith_g1(cos_v, alpha):
    tan2 = (1.0 - cos_v * cos_v) / (cos_v * cos_v)
    return 2.0 / (1.0 + math.sqrt(1.0 + alpha * alpha * tan2))


def _ggx(cos_m, alpha):
    tan2 = (1.0 - cos_m**2) / cos_m**2
    return alpha**2 / (math.pi * cos_m**4 * (alpha**2 + tan2) ** 2)


@pytest.mark.parametrize(("alpha", "degrees"), [(0.2, 30.0), (0.5, 60.0), (0.7, 80.0)])
def test_seen_obliquely_the_normals_are_ggxs_visible_ones(alpha, degrees):
    """The distribution of visible normals is G1(v) max(0, v.m) D(m) / (v.n) (Heitz 2014),
    integrated here over 6 x 6 cells of (theta, phi) by the midpoint rule, against the
    share of 40000 samples in each cell; the closed form itself integrates to 1."""
    theta_v = math.radians(degrees)
    v = np.array([math.sin(theta_v), 0.0, math.cos(theta_v)])
    steps = 600
    theta = (np.arange(steps) + 0.5) * (math.pi / 2) / steps
    phi = (np.arange(steps) + 0.5) * (2 * math.pi) / steps
    t, f = np.meshgrid(theta, phi, indexing="ij")
    m = np.stack([np.sin(t) * np.cos(f), np.sin(t) * np.sin(f), np.cos(t)], axis=-1)
    density = _smith_g1(v[2], alpha) * np.maximum(m @ v, 0.0) * _ggx(np.cos(t), alpha) / v[2]
    cell = density * np.sin(t) * (math.pi / 2 / steps) * (2 * math.pi / steps)
    assert cell.sum() == pytest.approx(1.0, abs=2e-3)
    expected = cell.reshape(6, steps // 6, 6, steps // 6).sum(axis=(1, 3))
    samples = _normals(tuple(v), alpha, 40000, seed=2)
    assert (samples @ v).min() >= 0.0
    s_theta = np.arccos(np.clip(samples[:, 2], -1.0, 1.0))
    s_phi = np.arctan2(samples[:, 1], samples[:, 0]) % (2 * math.pi)
    counts, _, _ = np.histogram2d(s_theta, s_phi, bins=6,
                                  range=[[0, math.pi / 2], [0, 2 * math.pi]])  # fmt: skip
    assert np.abs(counts / samples.shape[0] - expected).max() < 0.008


def test_a_frame_around_another_normal_turns_the_samples_with_it():
    """The same numbers about normal n give the head-on samples turned onto n."""
    n = tuple(np.array([1.0, 2.0, 2.0]) / 3.0)
    m = _normals(n, 0.4, 200, seed=4, n=n)
    assert (m @ np.array(n)).min() > 0.0
    cos_n = np.sort(m @ np.array(n))
    cos_z = np.sort(_normals(N, 0.4, 200, seed=4)[:, 2])
    np.testing.assert_allclose(cos_n, cos_z, atol=1e-12)


def _table_row(material):
    from core import Camera, RenderSettings, Scene, Sphere
    from core.compile import compile_scene
    from core.compile.materials import folded_row

    scene = Scene(Camera(), [Sphere("Ball", material, np.eye(4))])
    return folded_row(compile_scene(scene, RenderSettings(4, 4)).packed.materials, 0)


def test_a_surfaces_roughness_is_its_lobes_weighted_mean():
    """A constant graph folded into the table keeps its roughness: a rough metal's own, and
    a half-and-half Mix of a metal (0.6) and a glass (0.2) their mean, 0.4; the report's
    materials say theirs directly."""
    from core import Link, Material, ShaderNode

    metal = ShaderNode("principled", {"Metallic": 1.0, "Roughness": 0.35})
    assert _table_row(Material(surface=metal))["roughness"] == pytest.approx(0.35)
    mix = ShaderNode("mix_shader", {
        "Fac": 0.5,
        "Shader A": Link(ShaderNode("metallic", {"Roughness": 0.6}), "BSDF"),
        "Shader B": Link(ShaderNode("glass", {"Roughness": 0.2}), "BSDF"),
    })  # fmt: skip
    assert _table_row(Material(surface=mix))["roughness"] == pytest.approx(0.4)
    assert _table_row(Material(roughness=0.25))["roughness"] == 0.25


def test_a_rough_mirror_stays_sharp_without_glossy_samples_and_blurs_with_them():
    """A rough metal ball under a sky white above the horizon and black below: with no
    glossy samples its reflection's horizon is a sharp step (the sharp rule), as a
    roughness-0 ball's; with 64 it is a ramp over several pixels, and the ball reflects,
    summed over its pixels, within 5% as much (only the rays the lobe sends below the
    surface are lost)."""
    from core import Material, RenderSettings, Scene, ShaderNode, Sphere, render
    from tests.core.test_environment import look_at_ball

    world = _half_sky(1.0)

    def column(roughness, glossy):
        metal = ShaderNode("principled", {"Base Color": (0.9, 0.9, 0.9), "Metallic": 1.0,
                                          "Roughness": roughness})  # fmt: skip
        ball = Sphere("Ball", Material(surface=metal), np.eye(4))
        settings = RenderSettings(16, 16, pixel_samples=1, glossy_samples=glossy)
        image = render(Scene(look_at_ball(), [ball], environment=world), settings).image
        return image[:, 8, 0].astype(float)

    sharp, rough_sharp, rough_spread = column(0.0, 0), column(0.4, 0), column(0.4, 64)
    np.testing.assert_array_equal(rough_sharp, sharp)
    assert set(np.round(rough_sharp, 2)) <= {0.0, 0.9, 0.91}
    between = (rough_spread > 0.05) & (rough_spread < 0.8)
    assert between.sum() >= 3, rough_spread
    assert rough_spread.sum() == pytest.approx(sharp.sum(), rel=0.05)


def test_glossy_rays_go_where_the_light_goes():
    """A camera ray's hit spreads the setting's rays times the share of the light its lobes
    send on (core.kernels.integrator._glossy_samples): a rough metal ball all 64, a rough
    plastic ball (a specular layer reflecting 4-10%) a few, so that it costs little more than
    the sharp rule, while its blur still converges: the plastic's picture at 64 is closer
    to its own at 4,096 than the sharp rule's."""
    from core import Material, RenderSettings, Scene, ShaderNode, Sphere, render
    from tests.core.test_environment import look_at_ball

    world = _half_sky(4.0)  # bright enough that the blur shows in a plastic's layer

    def traced(surface, glossy):
        ball = Sphere("Ball", Material(surface=surface), np.eye(4))
        settings = RenderSettings(16, 16, pixel_samples=1, glossy_samples=glossy)
        result = render(Scene(look_at_ball(), [ball], environment=world), settings)
        return result.image.astype(float), result.stats.rays_traced

    metal = ShaderNode("principled", {"Metallic": 1.0, "Roughness": 0.4})
    plastic = ShaderNode("principled", {"Base Color": (0.1, 0.2, 0.6), "Roughness": 0.4})
    _, sharp_rays = traced(metal, 0)
    _, metal_rays = traced(metal, 64)
    plastic_sharp, plastic_sharp_rays = traced(plastic, 0)
    plastic_image, plastic_rays = traced(plastic, 64)
    converged, _ = traced(plastic, 4096)
    assert sharp_rays == plastic_sharp_rays
    # the rays spread beyond the sharp rule's one (less those a microfacet sends below the
    # surface, which are not traced)
    metal_extra = metal_rays - sharp_rays
    plastic_extra = plastic_rays - plastic_sharp_rays
    print(f"extra rays: metal {metal_extra}, plastic {plastic_extra}")
    assert 0 < plastic_extra < metal_extra / 6  # a few a hit, not 64
    error, sharp_error = (np.abs(x - converged).mean() for x in (plastic_image, plastic_sharp))
    print(f"plastic's error: 64 rays {error:.4f}, sharp {sharp_error:.4f}")
    assert error < 0.9 * sharp_error


def _half_sky(brightness):
    """A World of `brightness` above the horizon and black below."""
    from core import Environment, Texture

    sky = np.zeros((16, 32, 3))
    sky[:8] = brightness
    return Environment(colour=(1.0, 1.0, 1.0), image=Texture(pixels=sky, srgb=False))
