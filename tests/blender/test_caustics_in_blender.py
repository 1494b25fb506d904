"""Caustics through the add-on, against closed forms: a vertical mirror (a Glossy BSDF of
roughness 0, a plane mesh) in a sun 45 degrees from vertical throws a patch on the white
plane as bright again as the open plane (the sun directly, and once more by the mirror),
with Whitted's default Render settings (Light Paths > Caustics on); switched off, the patch
is gone."""

import math

import numpy as np
import pytest

from tests.support.cycles import SIZE, VIEW, add_light, mirror, new_scene, render_with, turned

pytestmark = pytest.mark.bpy


def _mirror_scene(bpy):
    scene = new_scene(bpy)
    mesh = bpy.data.meshes.new("Mirror")
    mesh.from_pydata([(0, -1, 0), (0, 1, 0), (0, 1, 2), (0, -1, 2)], [], [(0, 1, 2, 3)])
    mesh.materials.append(mirror(bpy))
    obj = bpy.data.objects.new("Mirror", mesh)
    obj.visible_camera = False
    scene.collection.objects.link(obj)
    add_light(bpy, scene, "SUN", (0.0, 0.0, 5.0), turned(0.0, 45.0), energy=2.0, angle=0.0)
    scene.whitted.shadow_samples = 1
    return scene


def _patch_and_open(image):
    centre = (np.arange(SIZE) + 0.5) / SIZE * VIEW - VIEW / 2.0
    x, y = np.meshgrid(centre, -centre)
    grey = image.mean(axis=-1)
    patch = (x > 0.3) & (x < 1.7) & (np.abs(y) < 0.7)
    open_plane = (x > 2.3) & (np.abs(y) > 1.3)
    return grey[patch].mean(), grey[open_plane].mean()


def test_a_mirrors_sun_patch_is_the_sun_again(bpy_with_whitted, tmp_path):
    bpy = bpy_with_whitted
    scene = _mirror_scene(bpy)
    patch, open_plane = _patch_and_open(render_with(bpy, scene, "WHITTED", tmp_path / "on.exr"))
    print(f"patch / open: {patch / open_plane:.4f}")
    assert math.isclose(patch / open_plane, 2.0, rel_tol=0.04)
    # the sun at 45 degrees on a white plane: E cos 45 / pi
    assert math.isclose(open_plane, 2.0 * math.cos(math.radians(45.0)) / math.pi, rel_tol=0.01)
    scene.whitted.use_caustics_reflective = False
    patch, open_plane = _patch_and_open(render_with(bpy, scene, "WHITTED", tmp_path / "off.exr"))
    assert math.isclose(patch / open_plane, 1.0, rel_tol=0.01)
