"""Render passes (RenderSettings.passes, core.passes) against closed forms computed here in
plain Python, ray by ray: every grid camera ray of every pixel is intersected with the
spheres exactly, and each pass is built from those hits as core.passes defines it (means of
the pixel's rays, or its nearest hit), then compared with what the kernels wrote.

Rays that graze a sphere too closely for float64 to decide are skipped, pixel by pixel."""

import math

import numpy as np
import pytest

import core
from core import Box, Camera, Material, PointLight, RenderSettings, Scene, SceneError, Sphere
from core.passes import (
    PASS_NAMES,
    TERMS,
    crypto_id,
    crypto_mask,
    crypto_metadata,
    hash_to_float,
    murmur3_32,
)
from tests.support.reference_tracer import camera_ray
from tests.support.scenes import translate_scale

CAMERA = Camera(eye=(0.0, 0.0, 6.0), view=(0.0, 0.0, -1.0), up=(0.0, 1.0, 0.0), fovy=40.0)
FORWARD = np.array([0.0, 0.0, -1.0])
WIDTH, HEIGHT, N = 32, 24, 3
BACKGROUND = (0.2, 0.4, 0.8)
BALL = (np.array([0.3, -0.2, 0.0]), 1.1)
SMALL = (np.array([-1.2, 0.6, 1.0]), 0.5)  # in front of the ball's left edge


def two_balls(small_holdout=False):
    ball = Sphere("Ball", Material(name="Red", pass_index=4), translate_scale(*BALL),
                  pass_index=2)  # fmt: skip
    small = Sphere("Small", Material(name="Blue", pass_index=9), translate_scale(*SMALL),
                   pass_index=5, holdout=small_holdout)  # fmt: skip
    return Scene(CAMERA, [ball, small], [], ambient=(0.1, 0.1, 0.1), background=BACKGROUND)


def settings(**changes):
    base = dict(width=WIDTH, height=HEIGHT, pixel_samples=N, passes=PASS_NAMES)
    return RenderSettings(**{**base, **changes})


def sphere_t(o, d, sphere):
    """(distance to the sphere along unit d, or None; whether the ray grazes it)."""
    centre, radius = sphere
    oc = o - centre
    b = float(np.dot(d, oc))
    discriminant = b * b - (float(np.dot(oc, oc)) - radius**2)
    close = abs(discriminant) < 1e-9
    if discriminant <= 0.0:
        return None, close
    t = -b - math.sqrt(discriminant)
    return (t if t > 0.0 else None), close


def pixel_rays(px, py, n=N):
    for s in range(n * n):
        fx, fy = (s % n + 0.5) / n, (s // n + 0.5) / n
        yield camera_ray(CAMERA.eye, CAMERA.view, CAMERA.up, CAMERA.fovy, WIDTH, HEIGHT,
                         px + fx - 0.5, py + fy - 0.5)  # fmt: skip


def nearest_hits(px, py, spheres, n=N):
    """Per camera ray of the pixel: (index of the nearest sphere met or None, its point, the
    ray's direction); and whether any ray grazed a sphere."""
    hits, close_any = [], False
    for o, d in pixel_rays(px, py, n):
        best = (None, math.inf)
        for k, sphere in enumerate(spheres):
            t, close = sphere_t(o, d, sphere)
            close_any |= close
            if t is not None and t < best[1]:
                best = (k, t)
        k, t = best
        hits.append((k, None if k is None else o + t * d, d))
    return hits, close_any


@pytest.fixture(scope="module")
def geometry_passes():
    return core.render(two_balls(), settings(mist_start=4.0, mist_depth=4.0,
                                             mist_falloff="LINEAR"))  # fmt: skip


def test_depth_position_and_indices_are_the_nearest_hits(geometry_passes):
    passes = geometry_passes.passes
    spheres = (BALL, SMALL)
    object_index, material_index = (2, 5), (4, 9)
    checked = 0
    for py in range(HEIGHT):
        for px in range(WIDTH):
            hits, close = nearest_hits(px, py, spheres)
            if close:
                continue
            met = [
                (float(np.dot(p - CAMERA.eye, FORWARD)), p, k) for k, p, _ in hits if k is not None
            ]
            if not met:
                assert passes["depth"][py, px, 0] == np.float32(1e10)
                assert passes["object_index"][py, px, 0] == 0.0
                assert np.all(passes["position"][py, px] == 0.0)
                continue
            depth, p, k = min(met, key=lambda m: m[0])
            assert passes["depth"][py, px, 0] == pytest.approx(depth, rel=1e-6)
            np.testing.assert_allclose(passes["position"][py, px], p, atol=1e-5)
            assert passes["object_index"][py, px, 0] == object_index[k]
            assert passes["material_index"][py, px, 0] == material_index[k]
            checked += 1
    assert checked > 150


def test_normal_uv_and_mist_are_means_of_the_pixels_rays(geometry_passes):
    passes = geometry_passes.passes
    spheres = (BALL, SMALL)
    for py in range(HEIGHT):
        for px in range(WIDTH):
            hits, close = nearest_hits(px, py, spheres)
            if close:
                continue
            normal, uv, mist = np.zeros(3), np.zeros(3), 0.0
            for k, p, _ in hits:
                if k is None:
                    mist += 1.0
                    continue
                centre, radius = spheres[k]
                local = (p - centre) / radius
                normal += local
                z = max(-1.0, min(1.0, local[2]))
                u = math.atan2(local[1], local[0]) / (2 * math.pi) + 0.5
                if local[0] < 0 and abs(local[1]) < 1e-6:
                    break  # on the seam, where u wraps from 1 to 0
                uv += (u, 0.5 + math.asin(z) / math.pi, 1.0)
                distance = float(np.linalg.norm(p - CAMERA.eye))
                mist += min(1.0, max(0.0, (distance - 4.0) / 4.0))
            else:
                count = len(hits)
                np.testing.assert_allclose(passes["normal"][py, px], normal / count, atol=2e-6)
                np.testing.assert_allclose(passes["uv"][py, px], uv / count, atol=2e-6)
                assert passes["mist"][py, px, 0] == pytest.approx(mist / count, abs=2e-6)


def test_cryptomatte_names_resolve_to_their_exact_coverage(geometry_passes):
    passes = geometry_passes.passes
    spheres = (BALL, SMALL)
    masks = {
        ("crypto_object", "Ball"): 0,
        ("crypto_object", "Small"): 1,
        ("crypto_material", "Red"): 0,
        ("crypto_material", "Blue"): 1,
    }
    found = {key: crypto_mask(passes[key[0]], key[1]) for key in masks}
    partial = 0
    for py in range(HEIGHT):
        for px in range(WIDTH):
            hits, close = nearest_hits(px, py, spheres)
            if close:
                continue
            for key, k in masks.items():
                coverage = sum(hit[0] == k for hit in hits) / len(hits)
                assert found[key][py, px] == pytest.approx(coverage, abs=1e-7), (key, px, py)
                partial += 0.0 < coverage < 1.0
            # ranks in decreasing coverage
            coverages = passes["crypto_object"][py, px, 1::2]
            assert np.all(np.diff(coverages) <= 0.0)
    assert partial > 20
    assert crypto_mask(passes["crypto_object"], "Nobody").max() == 0.0


def test_the_manifest_and_ids_follow_the_cryptomatte_specification():
    # MurmurHash3_x86_32 test vectors
    assert murmur3_32(b"") == 0
    assert murmur3_32(b"", 1) == 0x514E28B7
    assert murmur3_32(b"hello") == 0x248BFA47
    assert murmur3_32(b"The quick brown fox jumps over the lazy dog") == 0x2E4FF723
    # the float conversion keeps the bits, but for exponents 0 and 255
    assert np.float32(hash_to_float(0x3F800000)) == np.float32(1.0)
    assert math.isfinite(hash_to_float(0x7F800001)) and hash_to_float(0x00000001) != 0.0
    metadata = crypto_metadata("ViewLayer.CryptoObject", ["Ball", "Small"])
    (prefix,) = {key.rsplit("/", 1)[0] for key in metadata}
    assert prefix == "cryptomatte/" + f"{murmur3_32(b'ViewLayer.CryptoObject'):08x}"[:7]
    assert metadata[prefix + "/name"] == "ViewLayer.CryptoObject"
    assert metadata[prefix + "/manifest"] == (
        f'{{"Ball": "{murmur3_32(b"Ball"):08x}", "Small": "{murmur3_32(b"Small"):08x}"}}'
    )
    assert crypto_id("Ball") == hash_to_float(murmur3_32(b"Ball"))


def lit_sphere(material):
    ball = Sphere("Ball", material, translate_scale(*BALL))
    light = PointLight((2.0, 3.0, 5.0), (0.9, 0.8, 0.7))
    return Scene(CAMERA, [ball], [light], ambient=(0.1, 0.2, 0.3), background=BACKGROUND)


def expected_terms(px, py, material, light):
    """Combined's terms of one pixel by the report's lighting, in closed form: a lone convex
    sphere never shadows itself, and its mirror and glass (of index 1) see the background."""
    hits, close = nearest_hits(px, py, (BALL,))
    terms = {name: np.zeros(3) for name in TERMS}
    kd, ks = np.array(material.diffuse), np.array(material.specular)
    opacity = 1.0 - material.transparency
    background = np.array(BACKGROUND)
    for k, p, d in hits:
        if k is None:
            terms["environment"] += background
            continue
        n = (p - BALL[0]) / BALL[1]
        to_light = np.array(light.position) - p
        l_dir = to_light / np.linalg.norm(to_light)
        terms["ambient"] += opacity * kd * np.array((0.1, 0.2, 0.3))
        n_dot_l = float(np.dot(n, l_dir))
        if n_dot_l > 0.0:
            intensity = np.array(light.intensity)
            terms["diffuse"] += opacity * kd * n_dot_l * intensity
            r = 2.0 * n_dot_l * n - l_dir
            r_dot_v = float(np.dot(r, -d))
            if r_dot_v > 0.0:
                terms["specular"] += opacity * ks * r_dot_v**material.shininess * intensity
        terms["reflection"] += opacity * material.reflectivity * background
        terms["refraction"] += material.transparency * background
    return {name: value / len(hits) for name, value in terms.items()}, close


@pytest.mark.parametrize(
    "material",
    [
        Material(
            diffuse=(0.6, 0.3, 0.2), specular=(0.4, 0.4, 0.4), shininess=10.0, reflectivity=0.25
        ),  # fmt: skip
        Material(diffuse=(0.6, 0.3, 0.2), transparency=1.0, inner_ior=1.0),
    ],
    ids=["mirror", "glass of index 1"],
)
def test_the_terms_match_closed_forms_and_sum_to_combined(material):
    scene = lit_sphere(material)
    output = core.render(scene, settings())
    passes = output.passes
    total = sum(passes[name] for name in TERMS)
    np.testing.assert_allclose(total, output.image[..., :3], rtol=1e-5, atol=1e-6)
    for py in range(HEIGHT):
        for px in range(WIDTH):
            terms, close = expected_terms(px, py, material, scene.lights[0])
            if close:
                continue
            for name, value in terms.items():
                np.testing.assert_allclose(passes[name][py, px], value, atol=2e-6,
                                           err_msg=f"{name} at {px, py}")  # fmt: skip
    if material.transparency == 1.0:
        assert passes["diffuse_color"].max() == 0.0 and passes["refraction"].max() > 0.1


def test_lights_in_blenders_units_and_the_world_split_into_terms_that_sum_to_combined():
    """A sphere light, a spot and a panel, and an environment: their light goes to the
    diffuse and specular terms (the World's to diffuse), its view to environment, and the
    terms still sum to Combined."""
    material = Material(diffuse=(0.6, 0.3, 0.2), specular=(0.4, 0.4, 0.4), shininess=10.0,
                        reflectivity=0.25)  # fmt: skip
    scene = lit_sphere(material)
    scene.lights = [
        core.SphereLight(position=(2.0, 3.0, 5.0), power=(90.0, 80.0, 70.0), radius=0.5),
        core.PanelLight(centre=(-2.0, 1.0, 4.0), power=(50.0,) * 3),
        core.SpotLight(
            position=(0.0, 4.0, 1.0),
            power=(60.0,) * 3,
            spot_size=90.0,
            world_to_light=((1, 0, 0), (0, 0, 1), (0, -1, 0)),
        ),  # fmt: skip
    ]
    scene.environment = core.Environment(colour=(0.2, 0.3, 0.4))
    output = core.render(scene, settings())
    passes = output.passes
    total = sum(passes[name] for name in TERMS)
    np.testing.assert_allclose(total, output.image[..., :3], rtol=1e-5, atol=1e-6)
    assert passes["diffuse"].max() > 0.1 and passes["specular"].max() > 0.01
    assert passes["environment"].max() == pytest.approx(0.4, rel=1e-6)


@pytest.mark.parametrize("model", ["EON", "FON"])
def test_a_rough_diffuse_lit_by_lights_and_the_world_is_all_diffuse(model):
    """A node material's Oren-Nayar diffuse (its light is not kd's Lambert) under a sphere
    light and a World: the Diffuse pass holds all of it, no Specular is left over, and the
    terms sum to Combined, in either model. Before, the Diffuse pass was Lambert's and the
    difference was lost."""
    rough = core.ShaderNode("diffuse", {"Color": (0.7, 0.4, 0.2), "Roughness": 0.9})
    scene = lit_sphere(Material(surface=rough))
    scene.lights = [core.SphereLight(position=(2.0, 3.0, 5.0), power=(90.0, 80.0, 70.0))]
    scene.environment = core.Environment(colour=(0.2, 0.3, 0.4))
    output = core.render(scene, settings(rough_diffuse=model, environment_samples=16))
    passes = output.passes
    total = sum(passes[name] for name in TERMS)
    np.testing.assert_allclose(total, output.image[..., :3], rtol=1e-5, atol=1e-6)
    assert passes["diffuse"].max() > 0.1
    assert passes["specular"].max() == 0.0


def test_the_shadow_pass_is_one_where_lit_and_zero_in_the_balls_shadow():
    floor = Box("Floor", Material(), np.diag([6.0, 6.0, 0.5, 1.0]))
    floor.world_from_object[2, 3] = -2.0  # its top at z = -1.5
    light = PointLight((1.0, 0.5, 4.0), (1.0, 1.0, 1.0))
    ball = Sphere("Ball", Material(), translate_scale(np.zeros(3), 1.0))
    scene = Scene(CAMERA, [ball, floor], [light], background=BACKGROUND)
    shadow = core.render(scene, settings(pixel_samples=1, passes=("shadow",))).passes["shadow"]
    shaded = lit = 0
    for py in range(HEIGHT):
        for px in range(WIDTH):
            ((o, d),) = pixel_rays(px, py, 1)
            t, close = sphere_t(o, d, (np.zeros(3), 1.0))
            if close:
                continue
            if t is not None:
                assert np.all(shadow[py, px] == 1.0)  # nothing stands between it and the light
                continue
            point = o + d * (-1.5 - o[2]) / d[2]
            if abs(point[0]) > 5.9 or abs(point[1]) > 5.9:
                continue
            to_light = np.array(light.position) - point
            distance = float(np.linalg.norm(to_light))
            t, close = sphere_t(point, to_light / distance, (np.zeros(3), 1.0))
            if close:
                continue
            blocked = t is not None and t < distance
            assert np.all(shadow[py, px] == (0.0 if blocked else 1.0)), (px, py)
            shaded += blocked
            lit += not blocked
    assert shaded > 10 and lit > 100


def test_a_holdout_cuts_an_exact_transparent_hole():
    plain = core.render(two_balls(), settings(pixel_samples=1))
    held = core.render(two_balls(small_holdout=True), settings(pixel_samples=1))
    holes = 0
    for py in range(HEIGHT):
        for px in range(WIDTH):
            hits, close = nearest_hits(px, py, (BALL, SMALL), 1)
            if close:
                continue
            if hits[0][0] == 1:
                assert np.all(held.image[py, px] == 0.0)
                assert held.passes["depth"][py, px, 0] == np.float32(1e10)
                assert held.passes["crypto_object"][py, px, 1] == 0.0
                holes += 1
            else:
                assert np.all(held.image[py, px] == plain.image[py, px])
    assert holes > 10


def test_passes_leave_combined_unchanged_bit_for_bit():
    glass = Material(diffuse=(0.3, 0.3, 0.3), transparency=0.8, inner_ior=1.5,
                     reflectivity=0.2, specular=(0.5, 0.5, 0.5), shininess=30)  # fmt: skip
    scene = lit_sphere(glass)
    scene.shapes.append(Sphere("Small", Material(), translate_scale(*SMALL)))
    without = core.render(scene, settings(passes=()))
    with_all = core.render(scene, settings())
    assert without.passes == {}
    assert np.array_equal(without.image, with_all.image)


def test_an_unknown_pass_is_refused_by_name():
    with pytest.raises(SceneError, match="unknown pass 'zdepth'.*depth, mist"):
        core.render(two_balls(), settings(passes=("zdepth",)))
    with pytest.raises(SceneError, match="name each pass once"):
        core.render(two_balls(), settings(passes=("depth", "depth")))
