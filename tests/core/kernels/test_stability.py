"""Stability where ray tracers fail: rims, apexes and grazing rays, scene scale (acne), and
the same pixels for any tiling, thread count or border, from any thread."""

import subprocess
import sys
import textwrap

import numpy as np
import pytest

from core import (
    AreaLight,
    Box,
    Camera,
    Cone,
    Cylinder,
    Material,
    Mesh,
    PointLight,
    RenderSettings,
    Scene,
    Sphere,
    Texture,
    Torus,
    TriangleMesh,
    render,
)
from tests.support.meshes import icosphere
from tests.support.probe import hits, packed_shapes
from tests.support.scenes import translate_scale

RNG = np.random.default_rng(5)


def rays_through(points, rng, distance=20.0):
    """Rays from random far-away points through `points`."""
    away = rng.normal(size=points.shape)
    away /= np.linalg.norm(away, axis=1, keepdims=True)
    return points + distance * away, -away


def unit_circle(n, rng):
    angle = rng.uniform(0, 2 * np.pi, n)
    return np.cos(angle), np.sin(angle)


def just_inside(kind, n, rng, inset=1e-9):
    """Points inside the shape within `inset` of a rim, an apex or the surface."""
    x, y = unit_circle(n, rng)
    r = 1.0 - inset
    if kind == "sphere":  # on the equator, where rays from above and below graze
        return np.stack([x, y, np.zeros(n)], axis=1) * r
    if kind == "cylinder":  # on the rims of both caps
        z = np.where(rng.uniform(size=n) < 0.5, -r, r)
        return np.stack([x * r, y * r, z], axis=1)
    if kind == "cone":  # half on the base rim, half just below the apex
        base = np.stack([x * r, y * r, np.full(n, -r)], axis=1)
        # 1e-6 below the apex, where the cone's radius is 5e-7: nearer, the squared radius
        # in the quadric (2.5e-13 here) sinks below float64's resolution of the O(1) terms,
        # and whether a ray through a 1e-9-wide tip hits is decided by rounding
        apex = np.stack([x * 1e-7, y * 1e-7, np.full(n, 1.0 - 1e-6)], axis=1)
        return np.where((np.arange(n) % 2 == 0)[:, None], base, apex)
    # box: near its edges and corners
    p = rng.uniform(-1, 1, size=(n, 3))
    p[:, :2] = np.sign(p[:, :2]) * r
    return p


@pytest.mark.parametrize("kind", ["sphere", "cylinder", "cone", "box"])
def test_no_holes_or_nans_at_rims_apexes_and_grazing_angles(kind):
    shape = {"sphere": Sphere, "cylinder": Cylinder, "cone": Cone, "box": Box}[kind]
    matrix = translate_scale((3.0, -2.0, 1.0), 1.0) @ np.diag([1.0, 2.0, 0.5, 1.0])
    packed = packed_shapes(shape(world_from_object=matrix))
    points = just_inside(kind, 20000, RNG)
    world = points @ matrix[:3, :3].T + matrix[:3, 3]
    origins, directions = rays_through(world, RNG)
    t, hit_shape, _ = hits(packed, origins, directions)
    assert np.all(hit_shape == 0), f"{np.sum(hit_shape != 0)} rays fell through a {kind}"
    assert np.all(np.isfinite(t))
    # Grazing: tangent rays and rays exactly at the apex give a hit or a miss, never a NaN
    exact = {"cone": (0.0, 0.0, 1.0), "sphere": (1.0, 0.0, 0.0)}.get(kind, (1.0, 0.0, 1.0))
    p = np.broadcast_to(matrix[:3, :3] @ exact + matrix[:3, 3], (2000, 3))
    origins, directions = rays_through(np.ascontiguousarray(p), RNG)
    t, hit_shape, _ = hits(packed, origins, directions)
    assert not np.any(np.isnan(t))


def scaled_scene(scale):
    """The same scene at any scale: shadows, a torus, a smooth mesh, a mirror, glass."""
    s = np.diag([scale, scale, scale, 1.0])
    vertices, triangles = icosphere(3)
    shapes = [
        Box("Ground", Material(diffuse=(0.7, 0.7, 0.7)),
            s @ translate_scale((0, 0, -1), 1.0) @ np.diag([20, 20, 1, 1])),
        Sphere("Ball", Material(diffuse=(0.8, 0.3, 0.2), specular=(0.5, 0.5, 0.5), shininess=30),
               s @ translate_scale((-1.5, 0, 1), 1.0)),
        Torus("Ring", Material(diffuse=(0.2, 0.6, 0.3), reflectivity=0.3),
              s @ translate_scale((1.5, 0, 0.5), 1.0), major_radius=1.0, minor_radius=0.4),
        Mesh("Blob", Material(diffuse=(0.3, 0.3, 0.9)), s @ translate_scale((0, 2.5, 1), 1.0),
             TriangleMesh(vertices, triangles, smooth=True)),
        Sphere("Glass", Material(diffuse=(0, 0, 0), transparency=0.9, inner_ior=1.5),
               s @ translate_scale((0, -2, 0.6), 0.6)),
    ]  # fmt: skip
    eye = np.array([2.0, -9.0, 5.0]) * scale
    camera = Camera(eye=tuple(eye), view=tuple(-eye), up=(0, 0, 1), fovy=40)
    light = PointLight(tuple(np.array([4.0, -3.0, 8.0]) * scale), (0.9, 0.9, 0.9), (1, 0, 0))
    return Scene(camera, shapes, [light], ambient=(0.15, 0.15, 0.15), background=(0.1, 0.1, 0.2))


def test_scale_changes_nothing_no_acne_no_speckled_shadows():
    """At scales 1e-3 .. 1e4 the images agree with scale 1: fewer than 0.5% of pixels (the
    silhouettes, where rounding may flip a pixel) differ by more than 1e-3."""
    settings = RenderSettings(80, 60, max_depth=3, pixel_samples=1, shadow_samples=16)
    reference = render(scaled_scene(1.0), settings).image
    for scale in (1e-3, 1e3, 1e4):
        image = render(scaled_scene(scale), settings).image
        differ = np.abs(image - reference).max(axis=2) > 1e-3
        assert differ.mean() < 0.005, f"scale {scale}: {differ.sum()} pixels differ"


def everything_scene(tmp_path):
    texture_file = tmp_path / "checker.png"
    from PIL import Image

    checker = (np.indices((8, 8)).sum(axis=0) % 2 * 255).astype(np.uint8)
    Image.fromarray(np.stack([checker] * 3, axis=2)).save(texture_file)
    scene = scaled_scene(1.0)
    scene.shapes[1].material.texture = Texture(texture_file)
    scene.lights.append(AreaLight((0, 0, 6), (2, 0, 0), (0, 2, 0), (0.5, 0.5, 0.5), (1, 0, 0)))
    scene.camera.aperture_radius = 0.2
    scene.camera.focal_distance = 9.0
    return scene


def test_same_pixels_for_any_tiling_threads_and_border_with_every_random_feature(tmp_path):
    scene = everything_scene(tmp_path)
    common = dict(pixel_samples=2, pixel_sampling="jittered", shadow_samples=4, max_depth=3)
    reference = render(
        scene,
        RenderSettings(48, 36, tile_size=48, threads=1, **common),
    ).image
    for tile, threads in ((5, 2), (16, 3)):
        settings = RenderSettings(48, 36, tile_size=tile, threads=threads, **common)
        np.testing.assert_array_equal(render(scene, settings).image, reference)
    border = RenderSettings(48, 36, tile_size=7, region=(9, 5, 20, 17), **common)
    np.testing.assert_array_equal(render(scene, border).image[5:22, 9:29], reference[5:22, 9:29])
    other_seed = RenderSettings(48, 36, seed=1, **common)
    assert not np.array_equal(render(scene, other_seed).image, reference)


def test_renders_started_from_two_non_main_threads_at_once_do_not_abort(tmp_path):
    """Blender renders from a worker thread, and may run a final render beside a viewport:
    numba's threading layer must survive it (run in a child so an abort cannot hide)."""
    script = textwrap.dedent(
        """
        import threading, numpy as np
        from core import RenderSettings, render
        from tests.core.kernels.test_stability import scaled_scene
        out = {}
        def run(name):
            settings = RenderSettings(40, 30, threads=2, pixel_samples=1, shadow_samples=16)
            out[name] = render(scaled_scene(1.0), settings).image
        threads = [threading.Thread(target=run, args=(n,)) for n in "ab"]
        [t.start() for t in threads]
        [t.join() for t in threads]
        assert np.array_equal(out["a"], out["b"]) and out["a"].any()
        print("ok")
        """
    )
    result = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True,
                            timeout=600)  # fmt: skip
    assert result.returncode == 0 and result.stdout.strip() == "ok", result.stderr[-2000:]
