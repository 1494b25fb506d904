"""A rough diffuse (core.kernels.rough_diffuse), side by side with Cycles
(tests/support/cycles.py): a ball of Diffuse BSDF at Roughness 0.8 under a sharp sun from
the side and a grey World, and (from 4.3, which brought the input) a Principled BSDF's
Diffuse Roughness. Cycles draws Fujii's Oren-Nayar before 4.3 and the energy-preserving
one from 4.3; Whitted follows the Blender it runs in (blender_addon/compat.py).

Before: Lambert's, with a warning naming the Roughness (the measure below: 0.55 in 4.2,
0.34 in 5.0; now 0.003-0.005 in 3.4, 4.2, 4.5, 5.0 and 5.2). The World's light is sampled 1024
times a point: at the default 16 its grain alone reaches 0.08 in the dim blocks."""

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

TOLERANCE = 0.04  # of a 2 x 2 block's brightest channel (test_cycles_glints' measure)
COLOUR = (0.8, 0.45, 0.2, 1.0)


def _diffuse(bpy):
    material, _ = node_material(bpy, "Rough", "ShaderNodeBsdfDiffuse", Color=COLOUR,
                                Roughness=0.8)  # fmt: skip
    return material


def _principled(bpy):
    material, node = node_material(bpy, "Rough", "ShaderNodeBsdfPrincipled", Base_Color=COLOUR)
    if node.inputs.get("Diffuse Roughness") is None:
        pytest.skip("no Diffuse Roughness before Blender 4.3")
    node.inputs["Diffuse Roughness"].default_value = 0.8
    node.inputs["Specular IOR Level"].default_value = 0.0  # no specular layer: the diffuse alone
    return material


@pytest.mark.parametrize("make", [_diffuse, _principled], ids=["diffuse", "principled"])
def test_a_rough_diffuse_ball_is_lit_as_in_cycles(bpy_with_whitted, tmp_path, make):
    bpy = bpy_with_whitted
    scene = new_scene(bpy)
    bpy.data.objects.remove(bpy.data.objects["Plane"])
    add_ball(bpy, scene, make(bpy), location=(0.0, 0.0, 0.0), radius=3.5)
    uniform_world(scene, (0.1, 0.1, 0.1))
    scene.whitted.environment_samples = 1024  # the World-lit side as clean as Cycles' 256
    # from the camera's side and the right: Oren-Nayar's retro-reflection and its rim
    add_light(bpy, scene, "SUN", (0.0, 0.0, 5.0), turned(-60.0, 35.0), energy=3.0, angle=0.0)
    cycles, whitted = side_by_side(bpy, scene, tmp_path, samples=256)
    error = disagreement(cycles, whitted)
    print(f"{make.__name__}: {error:.4f}, brightest {cycles.max():.3f} / {whitted.max():.3f}")
    assert cycles.max() > 0.1
    assert error < TOLERANCE, error
