"""The Principled BSDF's Coat (Blender 4.0 on; core.kernels.clear_coat), side by side with
Cycles (tests/support/cycles.py):

- a rough coat over rough gold and over a blue plastic, lit by a point lamp without radius
  and a sun without angle under a black World: the coat's own GGX glint, and the layers
  below dimmed by what the coat reflects and tinted by its Coat Tint (no sample of a delta
  light is noisy);
- a sharp coat over a black base glowing in blue, in a grey World: the World in the coat's
  mirror (its exact Fresnel), the glow dimmed and tinted, the base's own specular layer
  under the coat.

Before issue 61's coat every one of these drew no coat at all, with a warning."""

import numpy as np
import pytest

from tests.blender.test_cycles_glints import disagreement
from tests.support.cycles import (
    add_ball,
    add_light,
    new_scene,
    node_material,
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


def _glow_under_sharp_coat(bpy):
    scene = new_scene(bpy)
    bpy.data.objects.remove(bpy.data.objects["Plane"])
    material = _coated(bpy, "Coated glow", Base_Color=(0.0, 0.0, 0.0), Roughness=0.0,
                       Emission_Color=(0.2, 0.6, 1.0), Emission_Strength=1.0, Coat_Weight=1.0,
                       Coat_Roughness=0.0, Coat_Tint=(0.9, 0.5, 0.3))  # fmt: skip
    add_ball(bpy, scene, material, location=(0.0, 0.0, 0.0), radius=3.5)
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
