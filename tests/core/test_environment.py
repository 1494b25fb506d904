"""The environment (Blender's World) against closed forms: the furnace (a white world gives a
white diffuse ball its albedo, exactly), a ball under a sky half white, half black, an image's
light found by importance sampling, and an image seen in a mirror ball against its lookup
computed here."""

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
    Sphere,
    Texture,
    render,
)

SIZE = 16


def look_at_ball(size=SIZE):
    """An orthographic view of a unit ball at the origin from -Y, framing it exactly."""
    camera = Camera(eye=(0.0, -10.0, 0.0), view=(0.0, 1.0, 0.0), up=(0.0, 0.0, 1.0),
                    projection="orthographic", ortho_height=2.0)  # fmt: skip
    return camera


def ball(material):
    return Sphere("Ball", material, np.eye(4))


def hits(size=SIZE):
    """Each pixel centre's point on the unit ball seen from -Y, and which pixels hit it."""
    c = ((np.arange(size) + 0.5) / size - 0.5) * 2.0
    x, z = np.meshgrid(c, -c)
    inside = x * x + z * z < 1.0
    y = -np.sqrt(np.clip(1.0 - x * x - z * z, 0.0, None))
    return np.stack([x, y, z], axis=-1), inside


def rendered(scene, samples=16, size=SIZE, pattern="stratified"):
    settings = RenderSettings(size, size, pixel_samples=1, environment_samples=samples,
                              shadow_sampling=pattern, max_depth=2)  # fmt: skip
    return render(scene, settings).image[..., :3].astype(float)


@pytest.mark.parametrize("pattern", ["stratified", "uniform", "halton"])
def test_the_furnace_a_white_world_gives_a_white_ball_its_albedo_exactly(pattern):
    albedo = (0.8, 0.5, 0.2)
    scene = Scene(look_at_ball(), [ball(Material(diffuse=albedo))],
                  environment=Environment(colour=(1.0, 1.0, 1.0)))  # fmt: skip
    image = rendered(scene, samples=3, pattern=pattern)
    _, inside = hits()
    np.testing.assert_allclose(
        image[inside], np.broadcast_to(albedo, image[inside].shape), rtol=1e-6
    )
    np.testing.assert_allclose(image[~inside], 1.0)  # the world behind it


def half_sky(height=64):
    """An equirectangular image: white above the horizon, black below."""
    pixels = np.zeros((height, 2 * height, 3))
    pixels[: height // 2] = 1.0
    return Texture(pixels=pixels, srgb=False)


def test_a_ball_under_a_white_upper_sky_gets_the_closed_form():
    # A sky of radiance 1 above the horizon: a normal at elevation a receives E / pi =
    # (1 + sin a) / 2 (the sky's view factor), and the ball does not shade itself there
    scene = Scene(look_at_ball(), [ball(Material(diffuse=(1.0, 1.0, 1.0)))],
                  environment=Environment(colour=(1.0, 1.0, 1.0), image=half_sky(256)))  # fmt: skip
    image = rendered(scene, samples=1024)[..., 0]
    points, inside = hits()
    expected = (1.0 + points[..., 2]) / 2.0
    # The image's horizon row is half a pixel's blur wide: rows near it are left out
    far = inside & (np.abs(points[..., 2]) < 0.97)
    np.testing.assert_allclose(image[far], expected[far], atol=0.01)
    assert abs(np.mean(image[far] - expected[far])) < 2e-3


def test_a_small_bright_sun_in_the_image_is_found_by_importance_sampling():
    # A sun of 3 x 3 pixels: with cosine-weighted directions few rays would find it; picked by
    # its light, every shading point gets it with little noise
    height = 64
    pixels = np.full((height, 2 * height, 3), 0.01)
    pixels[9:12, 39:42] = 500.0
    env = Environment(colour=(1.0, 1.0, 1.0), image=Texture(pixels=pixels, srgb=False))
    ground = Box("Ground", Material(diffuse=(1.0, 1.0, 1.0)), np.diag([50.0, 50.0, 1.0, 1.0]))
    ground.world_from_object[2, 3] = -1.0
    camera = Camera(eye=(0.0, 0.0, 10.0), view=(0.0, 0.0, -1.0), up=(0.0, 1.0, 0.0),
                    projection="orthographic", ortho_height=4.0)  # fmt: skip
    scene = Scene(camera, [ground], environment=env)
    # The irradiance on the plane z = 0 from the image, summed over its pixels exactly
    theta = np.pi * (np.arange(height) + 0.5) / height
    d_omega = (np.pi / height) * (2 * np.pi / (2 * height)) * np.sin(theta)
    above = np.cos(theta) * (theta < np.pi / 2)
    irradiance = np.sum(pixels[..., 0] * (above * d_omega)[:, None])
    noise = []
    for samples in (4, 64):
        image = rendered(scene, samples=samples)[..., 0]
        noise.append(image.std() / image.mean())
        np.testing.assert_allclose(image.mean(), irradiance / np.pi, rtol=0.02)
    # Most rays find the sun: 64 of them leave a tenth of noise (cosine-weighted directions
    # would leave it whole), and the noise falls as 1 / sqrt(rays)
    assert noise[1] < 0.1 and noise[1] < noise[0] / 3


def equirect_lookup(pixels, m):
    """Blender's equirectangular lookup of direction m, bilinear, repeating (the model's
    formula, computed here in numpy)."""
    h, w = pixels.shape[:2]
    u = (np.pi - np.arctan2(m[..., 1], m[..., 0])) / (2 * np.pi)
    v = 1.0 - np.arccos(np.clip(m[..., 2] / np.linalg.norm(m, axis=-1), -1, 1)) / np.pi
    x, y = u * w - 0.5, (1 - v) * h - 0.5
    x0, y0 = np.floor(x).astype(int), np.floor(y).astype(int)
    fx, fy = (x - x0)[..., None], (y - y0)[..., None]

    def texel(i, j):
        return pixels[j % h, i % w]

    top = texel(x0, y0) * (1 - fx) + texel(x0 + 1, y0) * fx
    bottom = texel(x0, y0 + 1) * (1 - fx) + texel(x0 + 1, y0 + 1) * fx
    return top * (1 - fy) + bottom * fy


def test_an_image_seen_in_a_mirror_ball_is_its_lookup_pixel_for_pixel():
    rng = np.random.default_rng(3)
    pixels = rng.random((32, 64, 3)) * 4.0
    turn = math.radians(30.0)
    rotation = np.array(
        [[math.cos(turn), -math.sin(turn), 0], [math.sin(turn), math.cos(turn), 0], [0, 0, 1]]
    )
    env = Environment(colour=(0.5, 1.0, 2.0), image=Texture(pixels=pixels, srgb=False),
                      direction_from_world=np.hstack([rotation, np.zeros((3, 1))]))  # fmt: skip
    mirror = Material(diffuse=(0.0, 0.0, 0.0), reflectivity=1.0)
    image = rendered(Scene(look_at_ball(), [ball(mirror)], environment=env), samples=0, size=32)
    points, inside = hits(32)
    view = np.array([0.0, 1.0, 0.0])
    reflected = view - 2 * (points @ view)[..., None] * points
    direction = np.where(inside[..., None], reflected, view)
    expected = equirect_lookup(pixels, direction @ rotation.T) * env.colour
    np.testing.assert_allclose(image, expected, rtol=2e-5, atol=1e-5)


def test_ray_visibility_hides_the_world_from_the_rays_switched_off():
    env = Environment(colour=(0.5, 0.6, 0.7))
    white, mirror = (
        Material(diffuse=(1.0, 1.0, 1.0)),
        Material(diffuse=(0.0,) * 3, reflectivity=1.0),
    )
    _, inside = hits()

    def image(material, **switches):
        for name, value in switches.items():
            setattr(env, name, value)
        picture = rendered(Scene(look_at_ball(), [ball(material)], environment=env), samples=4)
        for name in switches:
            setattr(env, name, True)
        return picture

    # Camera off: black behind the ball, which the World still lights
    hidden = image(white, camera=False)
    assert np.all(hidden[~inside] == 0.0)
    np.testing.assert_allclose(hidden[inside], image(white)[inside])
    # Diffuse off: the ball is unlit, the World still seen behind it
    unlit = image(white, diffuse=False)
    assert np.all(unlit[inside] == 0.0) and np.allclose(unlit[~inside], env.colour)
    # Glossy off: a mirror reflects black
    assert np.all(image(mirror, glossy=False)[inside] == 0.0)
    np.testing.assert_allclose(
        image(mirror)[inside], np.broadcast_to(env.colour, (inside.sum(), 3))
    )
