"""Blender's Fresnel and Layer Weight nodes side by side with Cycles (tests/support/cycles.py),
in every Blender version the tests run, as library materials use them:

- a ball whose Emission shows the node's output (directly, through a Color Ramp, as a
  Strength, inside a node group) seen straight down: each pixel Cycles' to float rounding
  (Cycles renders the ball's finely divided mesh, Whitted the exact sphere: the rim, where
  the two outlines differ and the value is steepest, is left out);
- the glass of old tutorials and asset packs (a Mix Shader of Refraction and Glossy by a
  Fresnel node) and a car paint (Diffuse under a Glossy coat by Layer Weight's Fresnel),
  on tests/blender/test_cycles_materials.py's ball over an emissive floor: every block
  within its tolerance.

Before, both nodes were named in a warning and their factor read as their input's value:
the glass was a half mirror, the paint a flat mix."""

import numpy as np
import pytest

from tests.blender.test_cycles_materials import assert_renders_as_in_cycles
from tests.support.cycles import SIZE, VIEW, add_ball, new_scene, side_by_side

pytestmark = pytest.mark.bpy

CLOSE = 2e-3  # of a pixel's value (0..2), as tests/blender/test_cycles_textures.py
# Pixels allowed past CLOSE, and by how much: the mesh's faces and smoothed normals stray
# from the sphere's (measured in 5.2: the ramp's one pixel of some 360 at 0.0021, where the
# rest lie within 0.0002 inside 0.7 of the radius). A wrong formula is off everywhere
STRAY_SHARE, STRAY_LARGEST = 0.01, 0.01
RADIUS = 3.0
RIM = 0.9  # pixels whose centre lies within this share of the ball's radius are compared
VARIES = 0.03  # the node's output spans more than this over them (15 times CLOSE)


def _fresnel(tree):
    node = tree.nodes.new("ShaderNodeFresnel")
    node.inputs["IOR"].default_value = 1.45
    return "Color", node.outputs["Fac"]


def _facing_ramp(tree):
    """Layer Weight's Facing through a two-colour ramp: a rim-light tint."""
    node = tree.nodes.new("ShaderNodeLayerWeight")
    node.inputs["Blend"].default_value = 0.3
    ramp = tree.nodes.new("ShaderNodeValToRGB")
    ramp.color_ramp.elements[0].color = (0.1, 0.2, 0.9, 1.0)
    ramp.color_ramp.elements[1].color = (1.0, 0.6, 0.1, 1.0)
    tree.links.new(node.outputs["Facing"], ramp.inputs[0])
    return "Color", ramp.outputs["Color"]


def _layer_fresnel_strength(tree):
    node = tree.nodes.new("ShaderNodeLayerWeight")
    node.inputs["Blend"].default_value = 0.3
    return "Strength", node.outputs["Fresnel"]


def _fresnel_in_a_group(tree):
    """As asset packs nest it: the Fresnel inside a group, its IOR given from outside."""
    import bpy

    from tests.blender.test_cycles_materials import _group

    group, group_in, group_out = _group(bpy, "Edge", [("IOR", "NodeSocketFloat")],
                                        [("Edge", "NodeSocketFloat")])  # fmt: skip
    fresnel = group.nodes.new("ShaderNodeFresnel")
    group.links.new(group_in.outputs[0], fresnel.inputs["IOR"])
    group.links.new(fresnel.outputs["Fac"], group_out.inputs[0])
    holder = tree.nodes.new("ShaderNodeGroup")
    holder.node_tree = group
    holder.inputs[0].default_value = 2.4
    return "Color", holder.outputs[0]


GRAPHS = {
    "fresnel": _fresnel,
    "layer_weight_facing_ramp": _facing_ramp,
    "layer_weight_fresnel_strength": _layer_fresnel_strength,
    "fresnel_in_a_group": _fresnel_in_a_group,
}


def _glowing_ball(bpy, scene, build):
    material, tree = _empty_material(bpy, "Facing")
    emission = tree.nodes.new("ShaderNodeEmission")
    role, socket = build(tree)
    tree.links.new(socket, emission.inputs[role])
    output = tree.nodes.new("ShaderNodeOutputMaterial")
    tree.links.new(emission.outputs[0], output.inputs[0])
    add_ball(bpy, scene, material, location=(0.0, 0.0, 3.5), radius=RADIUS)


@pytest.mark.parametrize("kind", list(GRAPHS))
def test_a_facing_graph_gives_cycles_pixels_on_a_ball(bpy_with_whitted, tmp_path, kind):
    bpy = bpy_with_whitted
    scene = new_scene(bpy)
    _glowing_ball(bpy, scene, GRAPHS[kind])
    cycles, whitted = side_by_side(bpy, scene, tmp_path, samples=16)
    centres = ((np.arange(SIZE) + 0.5) / SIZE - 0.5) * VIEW
    x, y = np.meshgrid(centres, centres)
    compared = np.hypot(x, y) < RIM * RADIUS
    off = np.abs(whitted - cycles).max(axis=-1)[compared]
    stray = (off > CLOSE).mean()
    print(f"{kind}: largest {off.max():.5f} within {RIM} of the radius, {stray:.4f} past "
          f"{CLOSE}; range {np.ptp(cycles[compared]):.3f}")  # fmt: skip
    assert np.ptp(cycles[compared][:, 0]) > VARIES  # the node's value varies over the ball
    assert stray <= STRAY_SHARE and off.max() <= STRAY_LARGEST, (stray, off.max())


def _empty_material(bpy, name):
    material = bpy.data.materials.new(name)
    material.use_nodes = True
    material.node_tree.nodes.clear()
    return material, material.node_tree


def _library_glass(bpy):
    """The glass of old tutorials and asset packs: Refraction and Glossy mixed by Fresnel."""
    material, tree = _empty_material(bpy, "Fresnel glass")
    fresnel = tree.nodes.new("ShaderNodeFresnel")
    fresnel.inputs["IOR"].default_value = 1.45
    refraction = tree.nodes.new("ShaderNodeBsdfRefraction")
    refraction.inputs["IOR"].default_value = 1.45
    glossy = tree.nodes.new("ShaderNodeBsdfGlossy")
    for node in (refraction, glossy):
        node.inputs["Color"].default_value = (1.0, 1.0, 1.0, 1.0)
        node.inputs["Roughness"].default_value = 0.0
    return _mixed(material, fresnel.outputs["Fac"], refraction, glossy)


def _car_paint(bpy):
    """A red Diffuse under a clear Glossy coat, mixed by Layer Weight's Fresnel."""
    material, tree = _empty_material(bpy, "Car paint")
    weight = tree.nodes.new("ShaderNodeLayerWeight")
    weight.inputs["Blend"].default_value = 0.2
    paint = tree.nodes.new("ShaderNodeBsdfDiffuse")
    paint.inputs["Color"].default_value = (0.6, 0.05, 0.05, 1.0)
    coat = tree.nodes.new("ShaderNodeBsdfGlossy")
    coat.inputs["Roughness"].default_value = 0.0
    coat.inputs["Color"].default_value = (1.0, 1.0, 1.0, 1.0)
    return _mixed(material, weight.outputs["Fresnel"], paint, coat)


def _mixed(material, factor, first, second):
    tree = material.node_tree
    mix = tree.nodes.new("ShaderNodeMixShader")
    tree.links.new(factor, mix.inputs[0])
    tree.links.new(first.outputs[0], mix.inputs[1])
    tree.links.new(second.outputs[0], mix.inputs[2])
    output = tree.nodes.new("ShaderNodeOutputMaterial")
    tree.links.new(mix.outputs[0], output.inputs[0])
    return material


MATERIALS = {"fresnel_glass": _library_glass, "car_paint": _car_paint}


@pytest.mark.parametrize("kind", list(MATERIALS))
def test_a_library_material_mixed_by_facing_renders_as_in_cycles(bpy_with_whitted, tmp_path, kind):
    assert_renders_as_in_cycles(bpy_with_whitted, tmp_path, kind, MATERIALS[kind])
