"""The Principled BSDF's Coat (Blender 4.0 on; core.kernels.clear_coat), side by side with
Cycles (tests/support/cycles.py):

- a rough coat over rough gold and over a blue plastic, lit by a point lamp without radius
  and a sun without angle under a black World: the coat's own GGX glint, and the layers
  below dimmed by what the coat reflects and tinted by its Coat Tint (no sample of a delta
  light is noisy);
- a sharp coat over a black base glowing in blue, in a grey World: the World in the coat's
  mirror (its exact Fresnel), the glow dimmed and tinted, the base's own specular layer
  under the coat.

- a floor seen at 45 degrees, its base normal-mapped, glowing under a sharp coat in a
  grey World: the coat keeps the smooth normal (Cycles' coat takes the surface's, not the
  Normal input's), and follows the map when it is linked to the Coat Normal too (the two
  differ by 0.065 in the measure below, in 5.2's Cycles: the test tells them apart).

Before issue 61's coat every one of these drew no coat at all, with a warning."""

import math

import numpy as np
import pytest

from tests.blender.test_cycles_bent_normals import _uv_floor
from tests.blender.test_cycles_glints import disagreement
from tests.support.cycles import (
    add_ball,
    add_light,
    new_scene,
    node_material,
    normal_map_image,
    side_by_side,
    turned,
    uniform_world,
)

pytestmark = pytest.mark.bpy

# of a 2 x 2 block's brightness, per channel (test_cycles_glints' measure)
TOLERANCE = 0.03


def _coated(bpy, name, **inputs):
    return node_material(bpy, name, "ShaderNodeBsdfPrincipled", **inputs)[0]


def _gold_under_rough_coat(bpy):
    return _coated(bpy, "Coated gold", Base_Color=(1.0, 0.77, 0.34), Metallic=1.0,
                   Roughness=0.4, Coat_Weight=1.0, Coat_Roughness=0.25,
                   Coat_Tint=(0.9, 0.8, 0.6))  # fmt: skip


def _plastic_under_rough_coat(bpy):
    return _coated(bpy, "Coated plastic", Base_Color=(0.1, 0.2, 0.6), Roughness=0.5,
                   Coat_Weight=0.8, Coat_Roughness=0.3, Coat_IOR=1.8,
                   Coat_Tint=(0.6, 0.9, 0.7))  # fmt: skip


def _lit_by_lamps(bpy, make_material):
    scene = new_scene(bpy)
    bpy.data.objects.remove(bpy.data.objects["Plane"])
    add_ball(bpy, scene, make_material(bpy), location=(0.0, 0.0, 0.0), radius=3.5)
    add_light(bpy, scene, "POINT", (6.0, 3.0, 8.0), energy=4000.0, shadow_soft_size=0.0)
    add_light(bpy, scene, "SUN", (0.0, 0.0, 5.0), turned(-50.0, 20.0), energy=3.0, angle=0.0)
    return scene


def _coated_glow(bpy):
    """A black base glowing in blue under a sharp tinted coat: (material, its node)."""
    return node_material(bpy, "Coated glow", "ShaderNodeBsdfPrincipled",
                         Base_Color=(0.0, 0.0, 0.0), Roughness=0.0,
                         Emission_Color=(0.2, 0.6, 1.0), Emission_Strength=1.0, Coat_Weight=1.0,
                         Coat_Roughness=0.0, Coat_Tint=(0.9, 0.5, 0.3))  # fmt: skip


def _glow_under_sharp_coat(bpy):
    scene = new_scene(bpy)
    bpy.data.objects.remove(bpy.data.objects["Plane"])
    add_ball(bpy, scene, _coated_glow(bpy)[0], location=(0.0, 0.0, 0.0), radius=3.5)
    uniform_world(scene, (0.5, 0.5, 0.5))
    return scene


SCENES = {
    "gold_under_rough_coat": lambda bpy: _lit_by_lamps(bpy, _gold_under_rough_coat),
    "plastic_under_rough_coat": lambda bpy: _lit_by_lamps(bpy, _plastic_under_rough_coat),
    "glow_under_sharp_coat": _glow_under_sharp_coat,
}


@pytest.mark.parametrize("kind", list(SCENES))
def test_a_coat_reflects_glints_and_layers_as_in_cycles(bpy_with_whitted, tmp_path, kind):
    bpy = bpy_with_whitted
    if bpy.app.version < (4, 0, 0):
        pytest.skip("the Principled BSDF's Coat came with Blender 4.0 (before: Clearcoat)")
    scene = SCENES[kind](bpy)
    cycles, whitted = side_by_side(bpy, scene, tmp_path, samples=64)
    error = disagreement(cycles, whitted)
    print(f"{kind}: {error:.4f}, brightest {cycles.max():.3f} / {whitted.max():.3f}")
    assert cycles.max() > 0.05
    assert np.isfinite(whitted).all()
    assert error < TOLERANCE, error


@pytest.mark.parametrize("mapped", ["base", "base_and_coat"])
def test_a_coat_over_a_normal_map_keeps_the_smooth_normal_as_in_cycles(
    bpy_with_whitted, tmp_path, mapped
):
    bpy = bpy_with_whitted
    if bpy.app.version < (4, 0, 0):
        pytest.skip("the Principled BSDF's Coat came with Blender 4.0 (before: Clearcoat)")
    scene = new_scene(bpy)
    bpy.data.objects.remove(bpy.data.objects["Plane"])
    uniform_world(scene, (0.5, 0.5, 0.5))
    material, principled = _coated_glow(bpy)
    tree = material.node_tree
    texture = tree.nodes.new("ShaderNodeTexImage")
    texture.image = normal_map_image(bpy, "Dents", seed=7, across=(0.1, 0.9), up=(0.6, 0.9))
    texture.interpolation = "Closest"
    normal_map = tree.nodes.new("ShaderNodeNormalMap")
    tree.links.new(texture.outputs["Color"], normal_map.inputs["Color"])
    tree.links.new(normal_map.outputs["Normal"], principled.inputs["Normal"])
    if mapped == "base_and_coat":
        tree.links.new(normal_map.outputs["Normal"], principled.inputs["Coat Normal"])
    _uv_floor(bpy, scene, material)
    tilt = math.radians(45.0)
    scene.camera.rotation_euler = (tilt, 0.0, 0.0)
    scene.camera.location = (0.0, -10.0 * math.sin(tilt), 10.0 * math.cos(tilt))
    cycles, whitted = side_by_side(bpy, scene, tmp_path, samples=64)
    error = disagreement(cycles, whitted)
    print(f"coat over a normal map ({mapped}): {error:.4f}")
    assert error < TOLERANCE, error
