"""Lighting and the ray tree against closed forms and numerical integrals: a plane under a
point light, an area light's irradiance, Fresnel, a refracting slab, mirrors, lenses."""

import math

import numpy as np
import pytest

from core import (
    AreaLight,
    Box,
    Camera,
    DirectionalLight,
    Material,
    Mesh,
    PointLight,
    RenderSettings,
    Scene,
    Sphere,
    TriangleMesh,
    render,
)
from core.kernels.integrator import fresnel_dielectric, refract
from core.kernels.trace import spawn_point
from tests.support.probe import light_through, packed_shapes, surface
from tests.support.reference_tracer import camera_ray
from tests.support.scenes import GROUND_KD, ground, look_down, translate_scale


def test_plane_under_a_point_light_matches_the_formula():
    light = PointLight((1.0, 2.0, 4.0), (30.0, 20.0, 10.0), (0.5, 0.2, 0.05))
    scene = Scene(look_down(), [ground()], [light], ambient=(0.1, 0.1, 0.1))
    width, height = 40, 30
    image = render(scene, RenderSettings(width, height, pixel_samples=1, shadow_samples=16)).image
    for px, py in np.random.default_rng(1).integers((0, 0), (width, height), size=(60, 2)):
        o, d = camera_ray(scene.camera.eye, scene.camera.view, scene.camera.up, 60.0, width,
                          height, px, py)  # fmt: skip
        p = o + d * (-o[2] / d[2])
        to_light = np.array(light.position) - p
        r = np.linalg.norm(to_light)
        c0, c1, c2 = light.attenuation
        expected = np.array(GROUND_KD) * (
            0.1 + np.array(light.intensity) * (to_light[2] / r) / (c0 + c1 * r + c2 * r * r)
        )
        np.testing.assert_allclose(image[py, px, :3], expected, rtol=1e-5)


def test_plane_under_a_directional_light_is_lit_by_the_cosine_and_shadowed():
    sun = DirectionalLight((1.0, -0.5, -2.0), (2.0, 1.5, 1.0))
    post = Sphere("Post", Material((0.9, 0.9, 0.9)), translate_scale((0.0, 0.0, 1.2), 1.0))
    scene = Scene(look_down(), [ground(), post], [sun], ambient=(0.1, 0.1, 0.1))
    width, height = 40, 30
    image = render(scene, RenderSettings(width, height, pixel_samples=1, shadow_samples=16)).image
    toward = -np.array(sun.direction) / np.linalg.norm(sun.direction)
    lit = np.array(GROUND_KD) * (0.1 + np.array(sun.intensity) * toward[2])
    dark = np.array(GROUND_KD) * 0.1
    checked = {"lit": 0, "shadow": 0}
    for px in range(width):
        for py in range(height):
            o, d = camera_ray(scene.camera.eye, scene.camera.view, scene.camera.up, 60.0,
                              width, height, px, py)  # fmt: skip
            p = o + d * (-o[2] / d[2])
            # The sun's ray from p passes the post (radius 1 around (0, 0, 1.2)) or not
            centre = np.array([0.0, 0.0, 1.2]) - p
            along = centre @ toward
            miss = np.linalg.norm(centre - along * toward)
            seen = np.array([0.0, 0.0, 1.2]) - o
            view_miss = np.linalg.norm(seen - (seen @ d) * d)
            if abs(miss - 1.0) < 0.02 or view_miss < 1.02:
                continue  # the shadow's rim, or the post itself in the way of the view
            expected, kind = (dark, "shadow") if miss < 1.0 and along > 0 else (lit, "lit")
            np.testing.assert_allclose(image[py, px, :3], expected, rtol=1e-5)
            checked[kind] += 1
    assert checked["lit"] > 500 and checked["shadow"] > 10


def area_light_integral(light, point, samples=96):
    """(1/A) integral over the light of cos(theta) / (c0 + c1 d + c2 d^2), Gauss-Legendre."""
    x, w = np.polynomial.legendre.leggauss(samples)
    s, t = np.meshgrid(x / 2, x / 2, indexing="ij")
    weight = np.outer(w, w) / 4
    q = (np.asarray(light.centre) + s[..., None] * np.asarray(light.edge_u)
         + t[..., None] * np.asarray(light.edge_v))  # fmt: skip
    to_light = q - point
    r = np.linalg.norm(to_light, axis=-1)
    c0, c1, c2 = light.attenuation
    f = np.maximum(to_light[..., 2] / r, 0.0) / (c0 + c1 * r + c2 * r * r)
    return np.sum(weight * f)


@pytest.fixture(scope="module")
def area_lit():
    light = AreaLight((0.5, 0.0, 2.0), (3.0, 1.0, 0.5), (-0.5, 2.0, 0.3), (5.0, 5.0, 5.0),
                      (1.0, 0.0, 0.3))  # fmt: skip
    scene = Scene(look_down(), [ground(Material(diffuse=(1.0, 1.0, 1.0)))], [light])
    pixels = np.random.default_rng(2).integers((0, 0), (32, 24), size=(40, 2))
    expected = []
    for px, py in pixels:
        o, d = camera_ray(scene.camera.eye, scene.camera.view, scene.camera.up, 60.0, 32, 24,
                          px, py)  # fmt: skip
        p = o + d * (-o[2] / d[2])
        expected.append(5.0 * area_light_integral(light, p))
    return scene, pixels, np.array(expected)


def area_errors(area_lit, sampling, samples, seed=0):
    scene, pixels, expected = area_lit
    settings = RenderSettings(
        32, 24, shadow_samples=samples, shadow_sampling=sampling, seed=seed, pixel_samples=1
    )
    image = render(scene, settings).image
    got = np.array([image[py, px, 0] for px, py in pixels])
    return (got - expected) / expected


def test_area_light_irradiance_matches_the_integral_within_half_a_percent(area_lit):
    errors = area_errors(area_lit, "stratified", 400)
    assert np.abs(errors).max() < 5e-3, errors


def test_stratified_area_light_sampling_beats_uniform(area_lit):
    stratified = np.sqrt(np.mean(area_errors(area_lit, "stratified", 64) ** 2))
    uniform = np.sqrt(np.mean(area_errors(area_lit, "uniform", 64) ** 2))
    assert stratified < 0.5 * uniform, (stratified, uniform)
    assert uniform < 0.05  # and uniform sampling is still an unbiased estimate


def test_fresnel_at_normal_incidence_and_brewster():
    f, cos_t = fresnel_dielectric(1.0, 1.0, 1.5)
    assert f == pytest.approx(((1.5 - 1.0) / 2.5) ** 2, rel=1e-12) and cos_t == 1.0
    brewster = math.atan(1.5)
    f, cos_t = fresnel_dielectric(math.cos(brewster), 1.0, 1.5)
    theta_t = math.asin(math.sin(brewster) / 1.5)
    rs = math.sin(theta_t - brewster) / math.sin(theta_t + brewster)
    assert f == pytest.approx(rs * rs / 2.0, rel=1e-12)  # p-polarised part vanishes
    assert cos_t == pytest.approx(math.cos(theta_t), rel=1e-12)


def test_total_internal_reflection_past_the_critical_angle():
    critical = math.asin(1.0 / 1.5)
    assert fresnel_dielectric(math.cos(critical + 1e-6), 1.5, 1.0) == (1.0, 0.0)
    just_inside, _ = fresnel_dielectric(math.cos(critical - 1e-3), 1.5, 1.0)
    assert 0.5 < just_inside < 1.0


def test_a_ray_through_a_glass_slab_exits_parallel_and_offset():
    """Into a slab of thickness 1 and out again: same direction, shifted sideways by
    thickness sin(i - t) / cos(t)."""
    slab = Box("Slab", Material(transparency=1.0, inner_ior=1.5), np.diag([50, 50, 0.5, 1.0]))
    packed = packed_shapes(slab)
    angle = math.radians(35.0)
    d = np.array([math.sin(angle), 0.0, -math.cos(angle)])
    o = np.array([0.0, 0.0, 3.0])
    _, _, p, n, _, _ = surface(packed, o, d)
    f, cos_t = fresnel_dielectric(-d @ n, 1.0, 1.5)
    inside_d = np.array(refract(tuple(d), tuple(n), 1.0 / 1.5, -d @ n, cos_t))
    start = np.array(spawn_point(tuple(p), tuple(-n), tuple(o)))
    _, _, q, n2, _, _ = surface(packed, start, inside_d)
    facing = -n2  # the exit face's normal, turned to face the ray inside
    _, cos_out = fresnel_dielectric(-inside_d @ facing, 1.5, 1.0)
    out_d = np.array(refract(tuple(inside_d), tuple(facing), 1.5, -inside_d @ facing, cos_out))
    np.testing.assert_allclose(out_d, d, atol=1e-14)
    theta_t = math.asin(math.sin(angle) / 1.5)
    shift = 1.0 * math.sin(angle - theta_t) / math.cos(theta_t)
    straight = o + d * ((q[2] - o[2]) / d[2])  # where the unbent ray would cross z = -0.5
    # to 1e-7: the refracted ray starts 1e-9 x |p| off the surface (the spawn offset)
    assert np.linalg.norm(q - straight) == pytest.approx(shift / math.cos(angle), rel=1e-7)
    assert q[2] == pytest.approx(-0.5, abs=1e-12)


def mirror_corridor(depth):
    """Two mirrors facing each other across x = +-2; the camera looks slightly sideways."""
    mirror = Material(diffuse=(0.2, 0.2, 0.2), reflectivity=0.8)
    walls = [Box(f"M{s}", mirror, translate_scale((s * 3.0, 0, 0), 1.0) @ np.diag([1, 30, 30, 1]))
             for s in (-1, 1)]  # fmt: skip
    camera = Camera(eye=(0, 0, 0), view=(1.0, 0.05, 0.0), up=(0, 0, 1), fovy=10)
    scene = Scene(camera, walls, [], ambient=(1.0, 1.0, 1.0), background=(0, 0, 0))
    return render(
        scene, RenderSettings(8, 8, max_depth=depth, pixel_samples=1, shadow_samples=16)
    ).image


def test_facing_mirrors_at_depth_fifty_terminate_each_bounce_darker():
    values = [mirror_corridor(depth)[4, 4, 0] for depth in (0, 1, 2, 3, 50)]
    image = mirror_corridor(50)
    assert np.all(np.isfinite(image))
    steps = np.diff(values[:4])
    assert np.all(steps > 0) and np.all(np.diff(steps) < 0)  # each bounce adds less
    # 0.2 (1 + 0.8 + ... + 0.8^50): the geometric series, to float32
    assert values[-1] == pytest.approx(0.2 * (1 - 0.8**51) / 0.2, rel=1e-5)


def lens_scene(aperture, focal_distance=10.0):
    near = Sphere("Near", Material(diffuse=(1, 0, 0)), translate_scale((0, 10, 0), 1.0))
    far = Sphere("Far", Material(diffuse=(0, 1, 0)), translate_scale((3, 30, 0), 2.0))
    camera = Camera(eye=(0, 0, 0), view=(0, 1, 0), up=(0, 0, 1), fovy=20,
                    aperture_radius=aperture, focal_distance=focal_distance)  # fmt: skip
    return Scene(camera, [near, far], [], ambient=(1, 1, 1), background=(0, 0, 0))


def test_zero_aperture_is_the_pinhole_image_exactly():
    settings = RenderSettings(40, 30, pixel_samples=2, pixel_sampling="jittered", shadow_samples=16)
    pinhole = render(lens_scene(0.0), settings).image
    for focal in (0.5, 10.0, 1e6):
        np.testing.assert_array_equal(render(lens_scene(0.0, focal), settings).image, pinhole)


def test_the_plane_in_focus_stays_sharp_and_the_rest_blurs():
    settings = RenderSettings(40, 30, pixel_samples=4, pixel_sampling="jittered", shadow_samples=16)
    pinhole = render(lens_scene(0.0), settings).image
    lens = render(lens_scene(0.4), settings).image
    near = pinhole[..., 0] > 0  # the red sphere, at the focal distance
    far = pinhole[..., 1] > 0
    sharp = np.abs(lens[..., 0] - pinhole[..., 0])[near].mean()
    blurred = np.abs(lens[..., 1] - pinhole[..., 1])[far].mean()
    assert sharp < 0.05 and blurred > 3 * sharp


def test_shadow_rays_through_glass_follow_the_documented_rule():
    """Each crossing of a surface with transparency tau passes tau of the light: through a
    sphere (two crossings) of tau = 0.5, a quarter; behind an opaque one, nothing."""
    glass = Sphere("Glass", Material(transparency=0.5, inner_ior=1.5))
    opaque = Sphere("Stone", Material(), translate_scale((0, 0, 5), 1.0))
    packed = packed_shapes(glass, opaque)
    assert light_through(packed, (0, 0, -3), (0, 0, 1), 4.5) == pytest.approx(0.25)
    assert light_through(packed, (0, 0, -3), (0, 0, 1), 3.5) == pytest.approx(0.5)  # ends inside
    assert light_through(packed, (0, 0, -3), (0, 0, 1), 10.0) == 0.0
    assert light_through(packed, (3, 0, -3), (0, 0, 1), 10.0) == 1.0


def test_a_shadow_ray_through_a_transparent_meshs_shared_edge_crosses_it_once():
    """A card of two triangles with transparency 0.5: a ray through their shared diagonal,
    or the corner they share, crosses the surface once and passes 0.5, as anywhere else
    on the card (each triangle reported the crossing: it passed 0.25). A closed mesh
    (a box) crossed through edges and corners passes 0.5 twice."""
    vertices = np.array([[-1, -1, 1], [1, -1, 1], [1, 1, 1], [-1, 1, 1]], float)
    card = Mesh("Card", Material(transparency=0.5),
                mesh=TriangleMesh(vertices, np.array([[0, 1, 2], [0, 2, 3]])))  # fmt: skip
    packed = packed_shapes(card)
    up = (0.0, 0.0, 1.0)
    for x, y in ((0.3, 0.3), (-0.6, -0.6), (1.0, 1.0), (0.3, -0.2)):
        assert light_through(packed, (x, y, 0.0), up, 5.0) == 0.5, (x, y)
    cube = Mesh("Cube", Material(transparency=0.5), mesh=_cube_mesh())
    packed = packed_shapes(cube)
    # through the middle of faces, along a face diagonal's edge, through two corners
    assert light_through(packed, (0.2, 0.1, -3.0), up, 6.0) == 0.25
    assert light_through(packed, (0.3, 0.3, -3.0), up, 6.0) == 0.25
    assert light_through(packed, (-1.0, -1.0, -3.0), up, 6.0) == 0.25


def _cube_mesh():
    """A closed cube [-1, 1]^3 of 12 triangles, each face split along a diagonal."""
    corners = np.array([[x, y, z] for z in (-1, 1) for y in (-1, 1) for x in (-1, 1)], float)
    quads = [(0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (2, 6, 7, 3), (0, 4, 6, 2), (1, 3, 7, 5)]
    faces = [t for a, b, c, d in quads for t in ((a, b, c), (a, c, d))]
    return TriangleMesh(corners, np.array(faces))


def test_a_surface_touching_a_pure_inverse_square_light_stays_finite():
    """c0 = 0 and a light near the surface: the falloff is capped (found by the fuzzer: a
    colour of 1e47 overflowed the float32 image to infinity)."""
    camera = Camera(eye=(0.0, -5.0, 0.0), view=(0.0, 1.0, 0.0), up=(0.0, 0.0, 1.0), fovy=30.0)
    ball = Sphere("Ball", Material((0.5, 0.5, 0.5), (1.0, 1.0, 1.0), 0.0))
    light = PointLight((0.0, -1.2, 0.0), (1.0, 1.0, 1.0), (0.0, 0.0, 1e-48))
    image = render(
        Scene(camera, [ball], [light]),
        RenderSettings(width=8, height=8, pixel_samples=1, shadow_samples=16),
    ).image
    assert np.all(np.isfinite(image))
    assert image[4, 4, 0] > 1e15  # blinding, as the formula says


def test_halton_area_light_sampling_converges_and_beats_uniform(area_lit):
    converged = area_errors(area_lit, "halton", 400)
    assert np.sqrt(np.mean(converged**2)) < 3e-3 and np.abs(converged).max() < 1e-2
    halton = np.sqrt(np.mean(area_errors(area_lit, "halton", 64) ** 2))
    uniform = np.sqrt(np.mean(area_errors(area_lit, "uniform", 64) ** 2))
    assert halton < 0.5 * uniform, (halton, uniform)


def test_random_pixel_sampling_averages_to_the_pixel_coverage():
    """n x n independent points per pixel: the edge of a large flat-lit square converges to
    its covered fraction like the other patterns, only with more noise."""
    camera = Camera(eye=(0.0, 0.0, 10.0), view=(0.0, 0.0, -1.0), up=(0.0, 1.0, 0.0), fovy=20.0)
    white = Material((1.0, 1.0, 1.0))
    # A square whose left edge falls 0.3 into a pixel column
    half = 10.0 * math.tan(math.radians(10.0))
    edge = -half + (8 + 0.3) * 2 * half / 16
    box = Box("B", white, np.diag([5.0, 5.0, 0.1, 1.0]))
    box.world_from_object[0, 3] = edge + 5.0
    scene = Scene(camera, [box], [], ambient=(1.0, 1.0, 1.0))
    columns = {}
    for sampling in ("grid", "jittered", "random"):
        settings = RenderSettings(
            16, 16, pixel_samples=16, pixel_sampling=sampling, shadow_samples=16
        )
        columns[sampling] = render(scene, settings).image[:, 8, 0]
    for sampling, column in columns.items():
        np.testing.assert_allclose(column.mean(), 0.7, atol=0.03, err_msg=sampling)
    assert columns["random"].std() > columns["jittered"].std()


def test_lens_cells_are_a_different_permutation_in_each_pixel():
    """Each pixel visits every lens cell once, in its own order (a fixed stride correlated
    pixel and lens positions for some n and biased the depth of field)."""
    from core.kernels.rng import permuted, sample_key

    for count in (1, 4, 9, 144, 256):
        orders = set()
        for px in range(4):
            key = np.uint64(sample_key(0, px, 7, count))
            order = [permuted(i, count, key) for i in range(count)]
            assert sorted(order) == list(range(count))
            orders.add(tuple(order))
        if count >= 9:
            assert len(orders) == 4  # each pixel its own order
