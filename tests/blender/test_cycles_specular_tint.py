"""Specular Tint (Blender 4.0 on) and the Metallic BSDF's Edge Tint, side by side with Cycles
(tests/support/cycles.py): sharp balls in a grey World, so that each pixel is the World
times the surface's Fresnel at that pixel's angle, in both renderers, with no noise:

- a dielectric whose Specular Tint colours its specular layer (Cycles keeps the real
  Fresnel's shape and tints its start; core.kernels.microfacet.tinted_fresnel);
- metals under Cycles' F82 tint, from the Principled BSDF's Specular Tint and from the
  Metallic BSDF's Edge Tint (microfacet.f82_dip).

Before: the dielectric's tint was drawn white (with a warning), the metals ran from the base
colour to the tint by Schlick's curve, 30% off near the rim. The rough ones, in a lamp and
the sun: tests/blender/test_cycles_glints.py."""

import pytest

from tests.blender.test_cycles_glints import disagreement
from tests.support.cycles import add_ball, new_scene, node_material, side_by_side, uniform_world

pytestmark = pytest.mark.bpy

TOLERANCE = 0.03  # of a 2 x 2 block's brightest channel (test_cycles_glints' measure)


def _principled(**inputs):
    return lambda bpy: node_material(bpy, "Tinted", "ShaderNodeBsdfPrincipled", Roughness=0.0,
                                     **inputs)[0]  # fmt: skip


def _metallic_bsdf(bpy):
    material, node = node_material(bpy, "Edge tinted", "ShaderNodeBsdfMetallic",
                                   Base_Color=(0.95, 0.64, 0.54), Edge_Tint=(0.6, 0.9, 0.5),
                                   Roughness=0.0)  # fmt: skip
    return material


BALLS = {
    "dielectric": _principled(Base_Color=(0.0, 0.0, 0.0), IOR=1.6, Specular_Tint=(1.0, 0.4, 0.1)),
    "principled_metal": _principled(
        Base_Color=(0.9, 0.6, 0.3), Metallic=1.0, Specular_Tint=(0.5, 0.8, 1.0)
    ),  # fmt: skip
    "metallic_bsdf": _metallic_bsdf,
}


@pytest.mark.parametrize("kind", list(BALLS))
def test_a_tinted_ball_reflects_the_world_as_in_cycles(bpy_with_whitted, tmp_path, kind):
    bpy = bpy_with_whitted
    if bpy.app.version < (4, 0, 0):
        pytest.skip("Specular Tint became a colour in Blender 4.0")
    if kind == "metallic_bsdf" and not hasattr(bpy.types, "ShaderNodeBsdfMetallic"):
        pytest.skip("no Metallic BSDF in this Blender")
    scene = new_scene(bpy)
    bpy.data.objects.remove(bpy.data.objects["Plane"])
    uniform_world(scene, (0.5, 0.5, 0.5))
    add_ball(bpy, scene, BALLS[kind](bpy), location=(0.0, 0.0, 0.0), radius=3.5)
    cycles, whitted = side_by_side(bpy, scene, tmp_path, samples=16)
    error = disagreement(cycles, whitted)
    print(f"{kind}: {error:.4f}, brightest {cycles.max():.3f} / {whitted.max():.3f}")
    assert cycles.max() > 0.05
    assert error < TOLERANCE, error
