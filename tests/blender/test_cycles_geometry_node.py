"""The Geometry node side by side with Cycles (tests/support/cycles.py): a ball seen from
above glowing with an output (a vector mapped to 0..1), and a plane seen from its back
glowing with Backfacing and its normals, which Cycles turns to face the ray. Before issue
61's Geometry node the node was named in a warning and its socket's value used: black."""

import math

import numpy as np
import pytest

from tests.support.cycles import VIEW, add_ball, new_scene, side_by_side

pytestmark = pytest.mark.bpy

CLOSE = 3e-3  # Cycles' mesh ball (256 x 128 faces) against Whitted's exact one


def _glowing(bpy, output, scale=0.5):
    """An Emission whose colour is the Geometry output times `scale` plus 0.5."""
    material = bpy.data.materials.new(output)
    material.use_nodes = True
    tree = material.node_tree
    tree.nodes.clear()
    geometry = tree.nodes.new("ShaderNodeNewGeometry")
    glow = tree.nodes.new("ShaderNodeEmission")
    if output == "Backfacing":
        tree.links.new(geometry.outputs[output], glow.inputs["Color"])
    else:
        mapped = tree.nodes.new("ShaderNodeVectorMath")
        mapped.operation = "MULTIPLY_ADD"
        mapped.inputs[1].default_value = (scale,) * 3
        mapped.inputs[2].default_value = (0.5,) * 3
        tree.links.new(geometry.outputs[output], mapped.inputs[0])
        tree.links.new(mapped.outputs["Vector"], glow.inputs["Color"])
    output_node = tree.nodes.new("ShaderNodeOutputMaterial")
    tree.links.new(glow.outputs[0], output_node.inputs["Surface"])
    return material


@pytest.mark.parametrize("output", ["Position", "Normal", "True Normal", "Incoming"])
def test_a_balls_geometry_glows_as_in_cycles(bpy_with_whitted, tmp_path, output):
    bpy = bpy_with_whitted
    scene = new_scene(bpy)
    bpy.data.objects.remove(bpy.data.objects["Plane"])
    scale = 0.1 if output == "Position" else 0.5
    add_ball(bpy, scene, _glowing(bpy, output, scale), location=(0.5, 0.0, 0.0), radius=3.0)
    cycles, whitted = side_by_side(bpy, scene, tmp_path, samples=4)
    size = cycles.shape[0]
    along = (np.arange(size) + 0.5) / size * VIEW - VIEW / 2.0
    x, y = np.meshgrid(along, -along)
    inside = (x - 0.5) ** 2 + y**2 < (0.9 * 3.0) ** 2  # clear of the rim
    # the mesh's faces against the exact sphere: its True Normal is the faces' own, and a few
    # of its smooth Normals differ by up to 0.004 in 5.0 (4 of 1,128 pixels)
    close = {"True Normal": 0.02, "Normal": 0.005}.get(output, CLOSE)
    assert np.ptp(cycles[inside][:, 0]) > 0.1 or output == "Incoming"  # the premise: it varies
    np.testing.assert_allclose(whitted[inside], cycles[inside], atol=close)


def test_a_plane_seen_from_behind_is_backfacing_as_in_cycles(bpy_with_whitted, tmp_path):
    bpy = bpy_with_whitted
    scene = new_scene(bpy)
    bpy.data.objects["Plane"].rotation_euler = (math.pi, 0.0, 0.0)  # facing down, away
    plane = bpy.data.objects["Plane"].data
    for output, expected in (("Backfacing", (1.0, 1.0, 1.0)), ("Normal", (0.5, 0.5, 1.0))):
        plane.materials.clear()
        plane.materials.append(_glowing(bpy, output))
        cycles, whitted = side_by_side(bpy, scene, tmp_path, samples=4)
        every = np.tile(expected, (cycles.size // 3, 1))
        for picture in (cycles, whitted):
            np.testing.assert_allclose(picture.reshape(-1, 3), every, atol=CLOSE)
