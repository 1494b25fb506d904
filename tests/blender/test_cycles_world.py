"""The World, rendered side by side by Cycles and Whitted (tests/support/cycles.py), in every
Blender version the tests run: a plain colour lighting a ball on a plane (occluded light
from the sky), an Environment Texture turned by a Mapping node lighting them, and the same
image seen in a mirror ball and behind it, pixel for pixel."""

import math

import numpy as np
import pytest

from tests.support.cycles import (
    add_ball,
    brightness_ratios,
    environment_world,
    mirror,
    new_scene,
    side_by_side,
    uniform_world,
)
from tests.support.skies import sky

pytestmark = pytest.mark.bpy

TOLERANCE = 0.02


def test_a_plain_world_lights_a_ball_and_the_plane_under_it_as_in_cycles(
    bpy_with_whitted, tmp_path
):
    bpy = bpy_with_whitted
    scene = new_scene(bpy)
    uniform_world(scene, (0.5, 0.6, 0.8), strength=2.0)
    add_ball(bpy, scene, bpy.data.materials["White"])
    scene.whitted.environment_samples = 256
    cycles, whitted = side_by_side(bpy, scene, tmp_path)
    ratios, _ = brightness_ratios(cycles, whitted)
    assert len(ratios) == 64 and np.abs(ratios - 1.0).max() < TOLERANCE, ratios
    # The plane is darker under the ball, where the ball hides the sky
    assert whitted[16, 16].sum() > 0 and whitted[4, 4].sum() > whitted[16, 9].sum()


def test_an_environment_texture_lights_the_scene_as_in_cycles(bpy_with_whitted, tmp_path):
    bpy = bpy_with_whitted
    scene = new_scene(bpy)
    environment_world(bpy, scene, sky(), turn_degrees=30.0)
    add_ball(bpy, scene, bpy.data.materials["White"])
    scene.whitted.environment_samples = 256
    cycles, whitted = side_by_side(bpy, scene, tmp_path, samples=2048)
    # 8 x 8 blocks: the small sun leaves both renderers noisier than a plain sky
    ratios, _ = brightness_ratios(cycles, whitted, block=8)
    assert len(ratios) == 16 and np.abs(ratios - 1.0).max() < TOLERANCE, ratios


def test_an_environment_texture_seen_in_a_mirror_ball_is_cycles_pixel_for_pixel(
    bpy_with_whitted, tmp_path
):
    bpy = bpy_with_whitted
    scene = new_scene(bpy)
    bpy.data.objects.remove(bpy.data.objects["Plane"])
    environment_world(bpy, scene, sky(), turn_degrees=30.0, strength=1.5)
    add_ball(bpy, scene, mirror(bpy), location=(0.0, 0.0, 0.0), radius=3.0)
    # Looking at the ball from the side, so the image's horizon and sun are in view
    camera = scene.camera
    camera.location, camera.rotation_euler = (0.0, -10.0, 0.0), (math.pi / 2, 0.0, 0.0)
    scene.whitted.environment_samples = 0
    cycles, whitted = side_by_side(bpy, scene, tmp_path, samples=16)
    ratio = whitted.sum(axis=-1) / cycles.sum(axis=-1)
    # (Cycles' ball is a fine mesh: a pixel straddling the sun's edge may differ)
    assert np.mean(np.abs(ratio - 1.0) < 0.01) > 0.97
    assert abs(np.median(ratio) - 1.0) < 2e-3


def test_the_worlds_ray_visibility_hides_it_as_in_cycles(bpy_with_whitted, tmp_path):
    """Camera off: black behind a mirror ball, which still reflects the World; then Glossy
    off: the ball reflects black; Diffuse off on a white ball: unlit."""
    bpy = bpy_with_whitted
    scene = new_scene(bpy)
    bpy.data.objects.remove(bpy.data.objects["Plane"])
    world = uniform_world(scene, (0.5, 0.6, 0.8), strength=2.0)
    ball = add_ball(bpy, scene, mirror(bpy), location=(0.0, 0.0, 0.0), radius=3.0)
    visibility = world.cycles_visibility
    visibility.camera = False
    cycles, whitted = side_by_side(bpy, scene, tmp_path, samples=16)
    np.testing.assert_allclose(whitted, cycles, atol=1e-5)
    assert whitted[0, 0].max() == 0.0 and whitted[16, 16].max() > 0.5
    visibility.glossy = False
    cycles, whitted = side_by_side(bpy, scene, tmp_path, samples=16)
    assert cycles.max() == 0.0 and whitted.max() == 0.0
    visibility.camera, visibility.glossy, visibility.diffuse = True, True, False
    ball.data.materials[0] = bpy.data.materials["White"]
    cycles, whitted = side_by_side(bpy, scene, tmp_path, samples=16)
    np.testing.assert_allclose(whitted, cycles, atol=1e-5)
    assert whitted[16, 16].max() == 0.0 and whitted[0, 0].max() > 0.5
