"""What Blender's node materials add to the report's material (core.model.Material, the
integrator's formula), against closed forms: a ball seen orthographically in a uniform World
of radiance L, so that every ray leaving the scene brings back L and a pixel is L times the
weights its rays carry, computed here from the hit's angle.

Schlick's tinted mirror, the clear coat's exact Fresnel, the glass tints over the series of
internal reflections, the Refraction BSDF's Fresnel-free refraction, emission, what passes
straight through (and its shadow), the holdout's alpha, and the rays that pass an object
they do not see."""

import math

import numpy as np
import pytest

from core import Box, Environment, Material, RenderSettings, Scene, SunLight, render
from tests.core.test_environment import ball, hits, look_at_ball

SIZE = 16
WORLD = 0.7  # the uniform World's radiance


def _render(shapes, depth=40, size=SIZE, passes=(), lights=()):
    scene = Scene(
        look_at_ball(), shapes, list(lights), environment=Environment(colour=(WORLD,) * 3)
    )
    settings = RenderSettings(size, size, pixel_samples=1, environment_samples=1,
                              max_depth=depth, passes=passes)  # fmt: skip
    return render(scene, settings)


def _cosines():
    """cos of the angle between the view ray and the ball's normal at each pixel."""
    points, inside = hits(SIZE)
    return -points[..., 1], inside


def _fresnel(cos_i, n1, n2):
    """The exact unpolarised dielectric reflectance, computed independently of the kernel."""
    sin_t = n1 / n2 * np.sqrt(np.clip(1.0 - cos_i**2, 0.0, None))
    cos_t = np.sqrt(np.clip(1.0 - sin_t**2, 0.0, None))
    rs = (n1 * cos_i - n2 * cos_t) / (n1 * cos_i + n2 * cos_t)
    rp = (n1 * cos_t - n2 * cos_i) / (n1 * cos_t + n2 * cos_i)
    return np.where(sin_t >= 1.0, 1.0, (rs * rs + rp * rp) / 2.0)


BLACK = dict(diffuse=(0.0, 0.0, 0.0))


def test_a_tinted_mirror_follows_schlicks_fresnel_from_its_colour_to_its_edge():
    normal, edge = np.array([0.9, 0.6, 0.2]), np.array([1.0, 0.95, 0.9])
    metal = Material(**BLACK, reflectivity=1.0, mirror_colour=tuple(normal),
                     mirror_edge=tuple(edge))  # fmt: skip
    image = _render([ball(metal)]).image[..., :3]
    cos, inside = _cosines()
    schlick = normal + (edge - normal) * ((1.0 - cos[..., None]) ** 5)
    np.testing.assert_allclose(image[inside], WORLD * schlick[inside], rtol=1e-5)


def test_a_clear_coat_reflects_the_exact_fresnel_and_hides_the_diffuse_below():
    kd = np.array([0.5, 0.25, 0.1])
    plastic = Material(diffuse=tuple(kd), coat=1.0, coat_ior=1.5, coat_hides=True)
    # World light on a diffuse point is sampled: use enough samples to be exact in a furnace
    scene = Scene(look_at_ball(), [ball(plastic)], environment=Environment(colour=(WORLD,) * 3))
    settings = RenderSettings(SIZE, SIZE, pixel_samples=1, environment_samples=4, max_depth=1)
    image = render(scene, settings).image[..., :3]
    cos, inside = _cosines()
    f = _fresnel(cos, 1.0, 1.5)[..., None]
    # the furnace: a white-lit Lambertian returns its albedo, here dimmed by the coat
    expected = WORLD * (f + kd * (1.0 - f))
    np.testing.assert_allclose(image[inside], expected[inside], rtol=1e-5)


def _glass_series(cos, ior, reflect, transmit, lost, depth):
    """The weight of a ball's rays that return to the World, through `depth` bounces, along
    the central column (cos 1 there only: used at the centre pixel)."""
    f = _fresnel(np.array(cos), 1.0, ior)
    total = f * reflect  # the outer reflection
    inside = (1.0 - lost * f) * transmit
    for _ in range(depth - 1):  # each internal bounce: out, or reflected on
        total = total + inside * (1.0 - lost * f) * transmit
        inside = inside * f * reflect
    return total


@pytest.mark.parametrize("refraction_fresnel", [1.0, 0.0])
def test_glass_tints_each_crossing_and_the_refraction_bsdf_loses_nothing_to_fresnel(
    refraction_fresnel,
):
    reflect, transmit = np.array([0.9, 0.8, 1.0]), np.array([0.5, 0.9, 0.7])
    glass = Material(**BLACK, transparency=1.0, outer_ior=1.0, inner_ior=1.5,
                     glass_reflect=tuple(reflect * refraction_fresnel),
                     glass_transmit=tuple(transmit),
                     refraction_fresnel=refraction_fresnel)  # fmt: skip
    image = _render([ball(glass)], size=SIZE + 1).image[..., :3]
    centre = image[SIZE // 2, SIZE // 2]  # an odd size: the centre pixel looks down the axis
    expected = WORLD * _glass_series(1.0, 1.5, reflect * refraction_fresnel, transmit,
                                     refraction_fresnel, depth=40)  # fmt: skip
    np.testing.assert_allclose(centre, expected, rtol=1e-6)
    if refraction_fresnel == 0.0:  # all refracts: a Refraction BSDF ball passes T^2 of it
        np.testing.assert_allclose(centre, WORLD * transmit**2, rtol=1e-6)


def test_emission_adds_its_radiance_and_its_own_pass():
    lamp = Material(**BLACK, emission=(2.0, 1.0, 0.5))
    result = _render([ball(lamp)], passes=("emission", "environment"))
    _, inside = _cosines()
    glow = np.broadcast_to((2.0, 1.0, 0.5), (int(inside.sum()), 3))
    np.testing.assert_allclose(result.image[..., :3][inside], glow)
    np.testing.assert_allclose(result.passes["emission"][inside], glow)
    np.testing.assert_allclose(result.passes["emission"][~inside], 0.0)


def test_what_passes_straight_through_sees_behind_and_lets_shadows_through():
    veil = Material(**BLACK, transparent=(0.5, 0.25, 1.0))
    image = _render([ball(veil)]).image[..., :3]
    _, inside = _cosines()
    # two surfaces crossed, each passing T of the light
    seen = np.broadcast_to(WORLD * np.array([0.25, 0.0625, 1.0]), (int(inside.sum()), 3))
    np.testing.assert_allclose(image[inside], seen, rtol=1e-6)
    # A floor lit by a sun straight above, under the ball: its shadow lets through T at
    # each of the two crossings, channel by channel (as Cycles has it)
    floor = Box("Floor", Material(diffuse=(1.0, 1.0, 1.0)),
                np.diag([5.0, 5.0, 0.1, 1.0]) @ _moved(0.0, 0.0, -20.0))  # fmt: skip
    sun = SunLight(direction=(0.0, 0.0, -1.0), irradiance=(math.pi,) * 3)
    scene = Scene(_from_above(), [ball(veil), floor], [sun])
    shade = render(scene, RenderSettings(SIZE, SIZE, pixel_samples=1)).image[..., :3]
    lit = shade[0, 0]  # a floor corner outside the shadow
    shadowed = shade[SIZE // 2, SIZE // 2]  # seen through the ball: T^2 of the shadowed floor
    np.testing.assert_allclose(shadowed, lit * np.array([0.25, 0.0625, 1.0]) ** 2, rtol=1e-6)


def _moved(x, y, z):
    m = np.eye(4)
    m[:3, 3] = (x, y, z)
    return m


def _from_above():
    from core import Camera

    return Camera(eye=(0.0, 0.0, 10.0), view=(0.0, 0.0, -1.0), up=(0.0, 1.0, 0.0),
                  projection="orthographic", ortho_height=2.0)  # fmt: skip


def test_a_holdout_share_cuts_alpha_and_the_colour_of_its_share():
    half = Material(diffuse=(0.0, 0.0, 0.0), emission=(0.5, 0.5, 0.5), holdout=0.5)
    image = _render([ball(half)]).image
    _, inside = _cosines()
    np.testing.assert_allclose(image[..., 3][inside], 0.5)
    np.testing.assert_allclose(image[..., 3][~inside], 1.0)


def test_rays_pass_an_object_their_kind_does_not_see():
    red = Material(diffuse=(0.0, 0.0, 0.0), emission=(1.0, 0.0, 0.0))
    hidden = ball(red)
    hidden.seen_by_camera = False
    image = _render([hidden]).image[..., :3]
    np.testing.assert_allclose(image, WORLD)  # the camera sees the World through it
    # Between the camera and a mirror ball, unseen by the camera: the centre pixel's ray
    # passes it, reflects straight back off the mirror, and meets it
    mirror = ball(Material(**BLACK, reflectivity=1.0))
    behind = ball(red)
    behind.world_from_object = _moved(0.0, -5.0, 0.0) @ np.diag([0.5, 0.5, 0.5, 1.0])
    behind.seen_by_camera = False
    centre = _render([mirror, behind], size=SIZE + 1).image[SIZE // 2, SIZE // 2, :3]
    np.testing.assert_allclose(centre, (1.0, 0.0, 0.0))
    behind.seen_in_mirrors = False
    centre = _render([mirror, behind], size=SIZE + 1).image[SIZE // 2, SIZE // 2, :3]
    np.testing.assert_allclose(centre, WORLD)
