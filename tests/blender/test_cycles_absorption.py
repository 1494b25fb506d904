"""A glass's Volume Absorption (core.kernels.absorption: Beer-Lambert inside, exact), side by
side with Cycles (tests/support/cycles.py): a sharp glass ball in a grey World, each pixel
the World through the ball, its light absorbed along every chord inside, in both renderers.

- the Glass BSDF with a Volume Absorption on the Material Output's Volume, as users build it;
- glass as Blender's glTF importer makes it of KHR_materials_transmission and
  KHR_materials_volume (a Principled BSDF of Transmission 1 and a Volume Absorption of the
  attenuation colour, Density 1 / attenuation distance), put on the ball.

Before: the Volume was named in a warning and not rendered, the glass drawn clear (the
measure below: 0.88 of the brightest channel in Blender 4.2; now 0.02)."""

import json
import sys

import pytest

from tests.blender.test_cycles_glints import disagreement
from tests.support.cycles import add_ball, new_scene, node_material, side_by_side, uniform_world
from tests.support.gltf_files import import_gltf, write_quad

pytestmark = pytest.mark.bpy

TOLERANCE = 0.05  # of a 2 x 2 block's brightest channel (test_cycles_glints' measure)
COLOUR, DENSITY = (0.9, 0.5, 0.2), 0.25  # absorbs (0.025, 0.125, 0.2) per metre


def _glass_bsdf(bpy, tmp_path):
    material, glass = node_material(bpy, "Tinted glass", "ShaderNodeBsdfGlass", IOR=1.45,
                                    Roughness=0.0, Color=(1.0, 1.0, 1.0))  # fmt: skip
    tree = material.node_tree
    volume = tree.nodes.new("ShaderNodeVolumeAbsorption")
    volume.inputs["Color"].default_value = (*COLOUR, 1.0)
    volume.inputs["Density"].default_value = DENSITY
    output = next(n for n in tree.nodes if n.type == "OUTPUT_MATERIAL")
    tree.links.new(volume.outputs[0], output.inputs["Volume"])
    return material


def _gltf_glass(bpy, tmp_path):
    extensions = dict(
        KHR_materials_transmission=dict(transmissionFactor=1.0),
        KHR_materials_volume=dict(thicknessFactor=1.0, attenuationDistance=1.0 / DENSITY,
                                  attenuationColor=list(COLOUR)),
    )  # fmt: skip
    material = dict(name="Tinted glass", extensions=extensions, pbrMetallicRoughness=dict(
        baseColorFactor=[1.0, 1.0, 1.0, 1.0], metallicFactor=0.0, roughnessFactor=0.0))  # fmt: skip
    path = write_quad(tmp_path / "glass.gltf", material, [])
    gltf = json.loads(path.read_text())
    gltf["extensionsUsed"] = list(extensions)
    path.write_text(json.dumps(gltf))
    import_gltf(bpy, path)
    bpy.data.objects.remove(bpy.data.objects["Quad"])
    imported = bpy.data.materials["Tinted glass"]
    output = next(n for n in imported.node_tree.nodes if n.type == "OUTPUT_MATERIAL"
                  and n.inputs["Volume"].is_linked)  # fmt: skip
    assert output.inputs["Volume"].links[0].from_node.type == "VOLUME_ABSORPTION"
    return imported


GLASSES = {"glass_bsdf": _glass_bsdf, "gltf": _gltf_glass}


@pytest.mark.parametrize("kind", list(GLASSES))
def test_a_glass_ball_absorbs_inside_as_in_cycles(bpy_with_whitted, tmp_path, kind):
    bpy = bpy_with_whitted
    if kind == "gltf" and bpy.app.version < (4, 0, 0):
        pytest.skip("the glTF importer of Blender 3.4 makes no Volume Absorption")
    scene = new_scene(bpy)
    bpy.data.objects.remove(bpy.data.objects["Plane"])
    uniform_world(scene, (0.5, 0.5, 0.5))
    ball = add_ball(bpy, scene, GLASSES[kind](bpy, tmp_path), location=(0.0, 0.0, 0.0),
                    radius=3.5)  # fmt: skip
    export_material = sys.modules["whitted.export.material"]
    absorption = export_material.convert(ball.material_slots[0].material).absorption
    assert absorption == pytest.approx([(1.0 - c) * DENSITY for c in COLOUR], rel=1e-6)
    cycles, whitted = side_by_side(bpy, scene, tmp_path, samples=64)
    error = disagreement(cycles, whitted)
    print(f"{kind}: {error:.4f}, blue at the centre {cycles[16, 16, 2]:.3f} / "
          f"{whitted[16, 16, 2]:.3f}")  # fmt: skip
    assert cycles[16, 16, 2] < 0.7 * cycles[16, 16, 0]  # the premise: the blue is taken
    assert error < TOLERANCE, error
