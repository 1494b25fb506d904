"""The glint of a lamp and the sun on rough surfaces, side by side with Cycles
(tests/support/cycles.py): a rough ball alone under a black World, lit by a point lamp
without radius and a sun without angle, so that what Cycles draws is each lobe's microfacet
BSDF times the light, exactly (no sample of a delta light is noisy), and what Whitted draws
is core.kernels.microfacet's closed form. Before issue 61 Whitted drew a Phong lobe of the
same peak: a glint too narrow, with no tail and no energy for the light that bounces between
microfacets."""

import numpy as np
import pytest

from tests.support.cycles import (
    add_ball,
    add_light,
    block_means,
    new_scene,
    node_material,
    side_by_side,
    turned,
)

pytestmark = pytest.mark.bpy

# of a 2 x 2 block's brightness, per channel; measured in 4.2 and 5.2: 0.006-0.016 (a Phong
# lobe of the same peak, before: 0.18-1.0)
TOLERANCE = 0.03


def _principled(bpy, name, **inputs):
    return node_material(bpy, name, "ShaderNodeBsdfPrincipled", **inputs)


def _glossy(distribution, roughness, colour=(0.9, 0.9, 0.9)):
    def make(bpy):
        material, node = node_material(bpy, "Glossy", "ShaderNodeBsdfGlossy", Color=colour,
                                       Roughness=roughness)  # fmt: skip
        node.distribution = distribution
        return material

    return make


def _rough_gold(bpy):
    return _principled(bpy, "Gold", Base_Color=(1.0, 0.77, 0.34), Metallic=1.0,
                       Roughness=0.4)[0]  # fmt: skip


def _satin_steel(bpy):
    return _principled(bpy, "Steel", Base_Color=(0.6, 0.6, 0.62), Metallic=1.0,
                       Roughness=0.7)[0]  # fmt: skip


def _plastic(bpy):
    """Blender's new material as a user tints it: a dielectric, roughness 0.5."""
    return _principled(bpy, "Plastic", Base_Color=(0.1, 0.2, 0.6), Roughness=0.5)[0]


def _tinted_plastic(bpy):
    """A dielectric whose Specular Tint colours its specular layer (from Blender 4.0)."""
    return _principled(bpy, "Tinted plastic", Base_Color=(0.1, 0.2, 0.6), Roughness=0.5,
                       Specular_Tint=(1.0, 0.5, 0.2))[0]  # fmt: skip


def _tinted_gold(bpy):
    """A metal whose Specular Tint is F82's edge tint (from Blender 4.0)."""
    return _principled(bpy, "Tinted gold", Base_Color=(1.0, 0.77, 0.34), Metallic=1.0,
                       Roughness=0.4, Specular_Tint=(0.9, 0.6, 0.6))[0]  # fmt: skip


GLINTS = {
    "rough_gold": _rough_gold,
    "satin_steel": _satin_steel,
    "plastic": _plastic,
    "glossy_ggx": _glossy("GGX", 0.3),
    "glossy_multiscatter": _glossy("MULTI_GGX", 0.6),
    "glossy_beckmann": _glossy("BECKMANN", 0.3),
    "tinted_plastic": _tinted_plastic,
    "tinted_gold": _tinted_gold,
}


def disagreement(cycles, whitted, block=2):
    """Per block and channel, |Whitted - Cycles| over the block's brightest Cycles channel
    (at least 5% of the picture's brightest block), the largest."""
    c, w = block_means(cycles, block), block_means(whitted, block)
    scale = np.maximum(c.max(axis=-1, keepdims=True), 0.05 * c.max())
    return float((np.abs(w - c) / scale).max())


def _glint_scene(bpy, make_material):
    scene = new_scene(bpy)
    bpy.data.objects.remove(bpy.data.objects["Plane"])
    add_ball(bpy, scene, make_material(bpy), location=(0.0, 0.0, 0.0), radius=3.5)
    add_light(bpy, scene, "POINT", (6.0, 3.0, 8.0), energy=4000.0, shadow_soft_size=0.0)
    add_light(bpy, scene, "SUN", (0.0, 0.0, 5.0), turned(-50.0, 20.0), energy=3.0, angle=0.0)
    return scene


@pytest.mark.parametrize("kind", list(GLINTS))
def test_a_rough_surface_glints_in_a_lamp_and_the_sun_as_in_cycles(bpy_with_whitted, tmp_path,
                                                                    kind):  # fmt: skip
    bpy = bpy_with_whitted
    scene = _glint_scene(bpy, GLINTS[kind])
    cycles, whitted = side_by_side(bpy, scene, tmp_path, samples=64)
    error = disagreement(cycles, whitted)
    print(f"{kind}: {error:.4f}, brightest {cycles.max():.3f} / {whitted.max():.3f}")
    assert cycles.max() > 0.05  # the premise: the glints are there to compare
    assert error < TOLERANCE, error
