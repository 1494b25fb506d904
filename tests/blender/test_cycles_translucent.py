"""The Translucent BSDF (core.kernels.translucent), side by side with Cycles
(tests/support/cycles.py): the picture's plane, seen from above, is a sheet of paper lit
from below by a lamp, the sun and a grey World, a block under it shadowing its back; and
the same sheet as a Mix of Translucent and Diffuse, lit on both sides. Cycles draws it as a
diffuse transmission lobe, its direct light only at diffuse bounces 0, as Whitted does.

Before: the node was named in a warning and drawn black (the measure below: 1.0 and 0.98
in Blender 4.2; now 0.024 and 0.020)."""

import pytest

from tests.blender.test_cycles_glints import disagreement
from tests.support.cycles import (
    add_light,
    new_scene,
    node_material,
    side_by_side,
    turned,
    uniform_world,
)

pytestmark = pytest.mark.bpy

TOLERANCE = 0.04  # of a 2 x 2 block's brightest channel (test_cycles_glints' measure)


def _sheet(bpy, mixed):
    """The plane's new material: Translucent, or a Mix of it and a Diffuse BSDF."""
    material = bpy.data.materials.new("Paper")
    material.use_nodes = True
    tree = material.node_tree
    tree.nodes.clear()
    translucent = tree.nodes.new("ShaderNodeBsdfTranslucent")
    translucent.inputs["Color"].default_value = (0.9, 0.6, 0.2, 1.0)
    output = tree.nodes.new("ShaderNodeOutputMaterial")
    shader = translucent.outputs[0]
    if mixed:
        diffuse = tree.nodes.new("ShaderNodeBsdfDiffuse")
        diffuse.inputs["Color"].default_value = (0.2, 0.4, 0.8, 1.0)
        mix = tree.nodes.new("ShaderNodeMixShader")
        mix.inputs["Fac"].default_value = 0.4
        tree.links.new(translucent.outputs[0], mix.inputs[1])
        tree.links.new(diffuse.outputs[0], mix.inputs[2])
        shader = mix.outputs[0]
    tree.links.new(shader, output.inputs["Surface"])
    plane = bpy.data.objects["Plane"].data
    plane.materials.clear()
    plane.materials.append(material)


def _block_below(bpy, scene):
    """A black cube under the sheet's left half, between it and the lamp. Black: Cycles
    counts a translucent ray as a transmission bounce, not a diffuse one, so it would also
    draw the light a white block reflects onto the sheet's back (a diffuse bounce, measured
    25% of the light next to it), which Whitted does not trace (no diffuse bounces)."""
    mesh = bpy.data.meshes.new("Block")
    s = 1.0
    corners = [(x, y, z) for x in (-s, s) for y in (-s, s) for z in (-s, s)]
    faces = [(0, 1, 3, 2), (4, 6, 7, 5), (0, 4, 5, 1), (2, 3, 7, 6), (0, 2, 6, 4), (1, 5, 7, 3)]
    mesh.from_pydata(corners, [], faces)
    black, _ = node_material(bpy, "Black", "ShaderNodeBsdfDiffuse", Color=(0.0, 0.0, 0.0, 1.0))
    mesh.materials.append(black)
    block = bpy.data.objects.new("Block", mesh)
    scene.collection.objects.link(block)
    block.location = (-2.0, 0.5, -1.5)


@pytest.mark.parametrize("mixed", [False, True], ids=["translucent", "mixed_with_diffuse"])
def test_a_sheet_lit_from_behind_shines_through_as_in_cycles(bpy_with_whitted, tmp_path, mixed):
    bpy = bpy_with_whitted
    scene = new_scene(bpy)
    _block_below(bpy, scene)
    _sheet(bpy, mixed)
    uniform_world(scene, (0.05, 0.05, 0.05))
    # (placed so that no edge of the block's shadow runs through the pixels' centres, where
    # Cycles' samples straddle it)
    add_light(bpy, scene, "POINT", (1.0, -0.37, -3.0), energy=800.0, shadow_soft_size=0.0)
    # pointing up through the sheet (a sun shines along its local -Z)
    add_light(bpy, scene, "SUN", (0.0, 0.0, -5.0), turned(160.0, 15.0), energy=1.5, angle=0.0)
    if mixed:  # and its front
        add_light(bpy, scene, "SUN", (0.0, 0.0, 5.0), turned(25.0, -10.0), energy=1.0, angle=0.0)
    cycles, whitted = side_by_side(bpy, scene, tmp_path, samples=256)
    error = disagreement(cycles, whitted)
    print(f"{'mixed' if mixed else 'translucent'}: {error:.4f}, brightest "
          f"{cycles.max():.3f} / {whitted.max():.3f}")  # fmt: skip
    assert cycles.max() > 0.1  # the premise: light comes through
    assert error < TOLERANCE, error
