"""Lights in Blender's units against closed forms: a white Lambertian plane seen straight
down, each pixel against the irradiance E its point receives (the plane shows E / pi).

Exact references: a point and a sphere (P cos / (4 pi d^2)), a disk facing the point
(P cos / (4 pi (d^2 + r^2))), a spot light's mask, a rectangle (Lambert's polygon formula), a
sun's cone (S cos); an ellipse and Blender 3.x's sun by quadrature computed here."""

import math

import numpy as np
import pytest

from core import (
    Box,
    Camera,
    Material,
    PanelLight,
    RenderSettings,
    Scene,
    SphereLight,
    SpotLight,
    SunLight,
    render,
)

WHITE = Material(diffuse=(1.0, 1.0, 1.0), specular=(0.0, 0.0, 0.0), name="white")
SIZE, VIEW = 12, 6.0  # pixels across, and the scene units they cover


def plane():
    """A wide slab whose top face is z = 0."""
    m = np.diag([100.0, 100.0, 1.0, 1.0])
    m[2, 3] = -1.0
    return Box("Plane", WHITE, m)


def pixel_points():
    """The plane's point under each pixel centre of the orthographic view: (SIZE, SIZE, 3)."""
    centres = ((np.arange(SIZE) + 0.5) / SIZE - 0.5) * VIEW
    x, y = np.meshgrid(centres, -centres)
    return np.stack([x, y, np.zeros_like(x)], axis=-1)


def rendered(lights, shadow_samples=64, pattern="stratified", shapes=(), channels=1):
    """The plane under `lights` (and any `shapes`, which the camera should not see), times
    pi: the irradiance each pixel's point receives (red, or RGB with `channels` 3)."""
    camera = Camera(eye=(0.0, 0.0, 10.0), view=(0.0, 0.0, -1.0), up=(0.0, 1.0, 0.0),
                    projection="orthographic", ortho_height=VIEW)  # fmt: skip
    settings = RenderSettings(SIZE, SIZE, pixel_samples=1, shadow_samples=shadow_samples,
                              shadow_sampling=pattern)  # fmt: skip
    image = render(Scene(camera, [plane(), *shapes], lights), settings).image
    if channels == 3:
        return image[..., :3].astype(float) * math.pi
    return image[..., 0].astype(float) * math.pi


def assert_converged(got, expected, rtol=3e-3):
    """Each pixel within `rtol` of the closed form (Monte Carlo noise), and no bias: the mean
    ratio within a sixth of that."""
    np.testing.assert_allclose(got, expected, rtol=rtol)
    assert abs(np.mean(got / expected - 1.0)) < rtol / 6


def point_irradiance(position, intensity, radius_term=0.0):
    """I cos / (d^2 + radius_term) at every pixel point, cos from the plane's normal."""
    to_light = np.asarray(position, float) - pixel_points()
    d2 = np.sum(to_light**2, axis=-1)
    return intensity * (to_light[..., 2] / np.sqrt(d2)) / (d2 + radius_term)


def test_a_point_light_gives_the_inverse_square_law_exactly():
    light = SphereLight(position=(0.7, -0.4, 2.0), power=(100.0,) * 3)
    expected = point_irradiance(light.position, 100.0 / (4 * math.pi))
    np.testing.assert_allclose(rendered([light]), expected, rtol=2e-6)


def test_a_sphere_light_lights_as_its_centre_would():
    # A sphere wholly above a point's horizon gives exactly what a point at its centre gives
    light = SphereLight(position=(0.3, 0.2, 2.5), power=(80.0,) * 3, radius=0.8, soft_falloff=False)
    expected = point_irradiance(light.position, 80.0 / (4 * math.pi))
    assert_converged(rendered([light], 1024), expected)


def test_a_soft_falloff_light_is_a_disk_turned_to_the_point():
    light = SphereLight(position=(0.3, 0.2, 2.0), power=(80.0,) * 3, radius=1.0)
    expected = point_irradiance(light.position, 80.0 / (4 * math.pi), radius_term=1.0)
    assert_converged(rendered([light], 1024), expected)


def spot(**fields):
    # Pointing straight down: the light's -Z is the world's -Z
    base = dict(position=(0.0, 0.5, 2.0), power=(100.0,) * 3, spot_size=70.0, blend=0.4)
    return SpotLight(**{**base, **fields})


def spot_expected(light):
    to_point = pixel_points() - np.asarray(light.position)
    along = -to_point[..., 2] / np.linalg.norm(to_point, axis=-1)
    cos_half = math.cos(math.radians(light.spot_size) / 2)
    x = np.clip((along - cos_half) / ((1 - cos_half) * light.blend), 0.0, 1.0)
    mask = np.where(along > cos_half, x * x * (3 - 2 * x), 0.0)
    if light.cosine_falloff:
        mask *= along
    return point_irradiance(light.position, 100.0 / (4 * math.pi)) * mask


@pytest.mark.parametrize("cosine", [False, True])
def test_a_spot_light_fades_over_its_blend_as_blender_defines_it(cosine):
    light = spot(cosine_falloff=cosine)
    got = rendered([light])
    expected = spot_expected(light)
    np.testing.assert_allclose(got, expected, rtol=1e-6, atol=1e-9)
    assert (expected == 0).sum() > 20 and ((expected > 0) & (expected < expected.max() / 2)).any()


def test_a_scaled_spot_light_has_an_elliptic_cone():
    # Scaling the light by 2 along x widens its cone along x only
    light = spot(position=(0.0, 0.0, 2.0), blend=0.0, spot_size=50.0,
                 world_to_light=((0.5, 0, 0), (0, 1, 0), (0, 0, 1)))  # fmt: skip
    lit = rendered([light]) > 0
    across, along = lit[5, :].sum(), lit[:, 5].sum()
    assert across >= 2 * along - 1 and along >= 3


def polygon_irradiance(corners, point, radiance):
    """Lambert's formula: the irradiance on the plane z = 0 (normal +z) at `point` from a
    Lambertian polygon of `radiance` wholly above its horizon."""
    v = np.asarray(corners, float) - point
    total = 0.0
    for i in range(len(v)):
        a, b = v[i], v[(i + 1) % len(v)]
        angle = math.acos(np.clip(a @ b / np.linalg.norm(a) / np.linalg.norm(b), -1, 1))
        normal = np.cross(a, b)
        total += angle * normal[2] / np.linalg.norm(normal)
    return abs(total) * radiance / 2.0


def test_a_rectangle_light_matches_lamberts_polygon_formula():
    u, v = np.array([1.5, 0.3, 0.0]), np.array([-0.2, 1.0, 0.4])
    centre = np.array([0.4, -0.3, 1.6])
    # edge_u x edge_v points up, so it shines down
    light = PanelLight(centre=tuple(centre), edge_u=tuple(u), edge_v=tuple(v), power=(60.0,) * 3)
    radiance = 60.0 / (math.pi * light.area())
    corners = [centre + s * u / 2 + t * v / 2 for s, t in ((-1, -1), (1, -1), (1, 1), (-1, 1))]
    expected = np.array(
        [[polygon_irradiance(corners, p, radiance) for p in r] for r in pixel_points()]
    )
    assert_converged(rendered([light], 1024), expected)


def test_an_area_light_shines_from_one_side_only():
    down = PanelLight(centre=(0.0, 0.0, 1.5), power=(60.0,) * 3)
    up = PanelLight(centre=(0.0, 0.0, 1.5), edge_v=(0.0, -1.0, 0.0), power=(60.0,) * 3)
    assert rendered([down]).min() > 0.0
    assert np.all(rendered([up]) == 0.0)


def ellipse_irradiance(centre, a, b, point, radiance, n=160):
    """The irradiance at `point` from a horizontal Lambertian ellipse (semi-axes a along x,
    b along y) facing down, by Gauss-Legendre quadrature in polar coordinates."""
    rho, w_rho = np.polynomial.legendre.leggauss(n)
    rho, w_rho = (rho + 1) / 2, w_rho / 2
    phi = np.linspace(0, 2 * math.pi, 4 * n, endpoint=False)
    R, PHI = np.meshgrid(rho, phi)
    x = centre[0] + a * R * np.cos(PHI) - point[0]
    y = centre[1] + b * R * np.sin(PHI) - point[1]
    h = centre[2] - point[2]
    integrand = h * h / (x * x + y * y + h * h) ** 2 * a * b * R
    return radiance * np.sum(integrand * w_rho[None, :]) * (2 * math.pi / phi.size)


def test_an_ellipse_light_matches_quadrature():
    centre = (0.2, -0.1, 1.2)
    light = PanelLight(centre=centre, edge_u=(2.0, 0.0, 0.0), edge_v=(0.0, 1.0, 0.0),
                       shape="ellipse", power=(50.0,) * 3)  # fmt: skip
    radiance = 50.0 / (math.pi * light.area())
    expected = np.array(
        [[ellipse_irradiance(centre, 1.0, 0.5, p, radiance) for p in r] for r in pixel_points()]
    )
    assert_converged(rendered([light], 1024), expected)


def test_a_disk_light_matches_the_closed_form_for_a_parallel_disk():
    # A Lambertian disk of radius R facing down at height h: at horizontal distance rho,
    # E = (pi L / 2) (1 - (h^2 + rho^2 - R^2) / sqrt((h^2 + rho^2 + R^2)^2 - 4 rho^2 R^2))
    centre, radius = np.array([0.3, -0.2, 1.3]), 0.9
    diameter = 2 * radius
    light = PanelLight(centre=tuple(centre), edge_u=(diameter, 0.0, 0.0),
                       edge_v=(0.0, diameter, 0.0), shape="ellipse", power=(40.0,) * 3)  # fmt: skip
    radiance = 40.0 / (math.pi * light.area())
    offset = pixel_points() - centre
    h2, rho2, r2 = offset[..., 2] ** 2, offset[..., 0] ** 2 + offset[..., 1] ** 2, radius**2
    root = np.sqrt((h2 + rho2 + r2) ** 2 - 4 * rho2 * r2)
    expected = math.pi * radiance / 2 * (1 - (h2 + rho2 - r2) / root)
    assert_converged(rendered([light], 1024), expected)


def test_a_wide_sun_gives_its_irradiance_to_a_facing_plane():
    for angle in (0.0, 20.0, 90.0):
        sun = SunLight(direction=(0.0, 0.0, -1.0), irradiance=(3.0,) * 3, angle=angle)
        if angle == 0.0:
            np.testing.assert_allclose(rendered([sun]), 3.0, rtol=1e-6)
        else:
            assert_converged(rendered([sun], 1024), np.full((SIZE, SIZE), 3.0))


def test_a_tilted_sun_gives_the_cosine():
    # Cone of half-angle 15 degrees around a direction 40 degrees from the normal
    tilt = math.radians(40.0)
    sun = SunLight(direction=(math.sin(tilt), 0.0, -math.cos(tilt)), irradiance=(2.0,) * 3,
                   angle=30.0)  # fmt: skip
    assert_converged(rendered([sun], 1024), np.full((SIZE, SIZE), 2.0 * math.cos(tilt)))


def test_a_blender_3_sun_spreads_its_light_over_a_disk():
    # Blender 3.x: directions through a disk of radius tan(h), each carrying S
    sun = SunLight(irradiance=(1.0,) * 3, angle=90.0, sampling="disk")
    reach = math.tan(math.radians(45.0))
    expected = 2 * (math.sqrt(1 + reach**2) - 1) / reach**2
    assert_converged(rendered([sun], 1024), np.full((SIZE, SIZE), expected))


def test_lights_without_shadows_or_diffuse_light_do_as_switched():
    # A slab 1 above the plane, |x|, |y| < 0.4, under a point light at height 2: its shadow
    # covers |x|, |y| < 0.8 of the plane
    blocker = Box("Blocker", WHITE, np.diag([0.4, 0.4, 0.02, 1.0]))
    blocker.world_from_object[2, 3] = 1.0
    camera = Camera(eye=(0.0, 0.0, 10.0), view=(0.0, 0.0, -1.0), up=(0.0, 1.0, 0.0),
                    projection="orthographic", ortho_height=VIEW)  # fmt: skip
    settings = RenderSettings(SIZE, SIZE, pixel_samples=1)
    shaded = (5, 7)  # the plane's point (0.75, 0.25): beside the slab, in its shadow

    def image(**switches):
        lit = SphereLight(position=(0.0, 0.0, 2.0), power=(100.0,) * 3, **switches)
        scene = Scene(camera, [plane(), blocker], [lit])
        return render(scene, settings).image[..., 0].astype(float)

    with_shadow, without = image(), image(cast_shadow=False)
    assert with_shadow[shaded] == 0.0 and without[shaded] > 0.1
    outside = np.ones_like(with_shadow, bool)
    outside[3:9, 3:9] = False
    np.testing.assert_array_equal(with_shadow[outside], without[outside])
    assert np.all(image(diffuse=False) == 0.0)
