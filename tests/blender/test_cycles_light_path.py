"""Light Path's outputs side by side with Cycles (tests/support/cycles.py), beside the Is Camera
Ray test of test_cycles_materials.py: a probe glowing with three outputs as its colour,
seen from above directly (the picture's right half, under a Transparent sheet in one case)
and in a sharp mirror (the left half, the probe above the camera), so that each half is one
known colour in both renderers. Before issue 61's Light Path outputs only Is Camera Ray,
Is Shadow Ray and Ray Depth were read: the others were named in a warning and read as
their socket's value, 0."""

import numpy as np
import pytest

from tests.support.cycles import new_scene, node_material, side_by_side

pytestmark = pytest.mark.bpy

CLOSE = 2e-3  # Cycles' float32 lengths


def _square(bpy, scene, name, corners, material):
    mesh = bpy.data.meshes.new(name)
    mesh.from_pydata(corners, [], [(0, 1, 2, 3)])
    mesh.materials.append(material)
    scene.collection.objects.link(bpy.data.objects.new(name, mesh))


def _probe_material(bpy, outputs, scale):
    """An Emission whose colour is Combine XYZ of Light Path's `outputs` times `scale`."""
    material = bpy.data.materials.new("Probe")
    material.use_nodes = True
    tree = material.node_tree
    tree.nodes.clear()
    path = tree.nodes.new("ShaderNodeLightPath")
    combine = tree.nodes.new("ShaderNodeCombineXYZ")
    for k, (name, factor) in enumerate(zip(outputs, scale, strict=True)):
        times = tree.nodes.new("ShaderNodeMath")
        times.operation = "MULTIPLY"
        times.inputs[1].default_value = factor
        tree.links.new(path.outputs[name], times.inputs[0])
        tree.links.new(times.outputs[0], combine.inputs[k])
    glow = tree.nodes.new("ShaderNodeEmission")
    tree.links.new(combine.outputs[0], glow.inputs["Color"])
    output = tree.nodes.new("ShaderNodeOutputMaterial")
    tree.links.new(glow.outputs[0], output.inputs["Surface"])
    return material


CASES = {
    # (outputs, their scales, the left half's colour (by the mirror), the right half's: a
    # camera ray's length counts from the camera's Clip Start, 0.1, as Cycles clips)
    "reflection": (("Is Reflection Ray", "Is Glossy Ray", "Ray Length"), (1.0, 1.0, 0.05),
                   (1.0, 1.0, 0.6), (0.0, 0.0, 0.47)),
    "depths": (("Ray Depth", "Glossy Depth", "Transmission Depth"), (1.0, 1.0, 1.0),
               (1.0, 1.0, 0.0), (0.0, 0.0, 0.0)),
    "transparent": (("Is Camera Ray", "Transparent Depth", "Is Transmission Ray"),
                    (1.0, 1.0, 1.0), (0.0, 0.0, 0.0), (1.0, 1.0, 0.0)),
}  # fmt: skip


@pytest.mark.parametrize("case", list(CASES))
def test_light_path_outputs_read_as_in_cycles(bpy_with_whitted, tmp_path, case):
    bpy = bpy_with_whitted
    outputs, scale, by_mirror, direct = CASES[case]
    scene = new_scene(bpy)
    bpy.data.objects.remove(bpy.data.objects["Plane"])
    mirror, _ = node_material(bpy, "Mirror", "ShaderNodeBsdfGlossy", Roughness=0.0,
                              Color=(1.0, 1.0, 1.0, 1.0))  # fmt: skip
    probe = _probe_material(bpy, outputs, scale)
    _square(bpy, scene, "Mirror", [(-5, -5, 0), (0, -5, 0), (0, 5, 0), (-5, 5, 0)], mirror)
    # above the camera (z = 10), facing down: only the mirror sees it, 12 from it
    _square(bpy, scene, "Above", [(-9, -9, 12), (-9, 9, 12), (9, 9, 12), (9, -9, 12)], probe)
    _square(bpy, scene, "Beside", [(0, -5, 0.5), (5, -5, 0.5), (5, 5, 0.5), (0, 5, 0.5)], probe)
    if case == "transparent":
        veil, _ = node_material(bpy, "Veil", "ShaderNodeBsdfTransparent",
                                Color=(1.0, 1.0, 1.0, 1.0))  # fmt: skip
        _square(bpy, scene, "Veil", [(0, -5, 3), (5, -5, 3), (5, 5, 3), (0, 5, 3)], veil)
    cycles, whitted = side_by_side(bpy, scene, tmp_path, samples=4)
    half = cycles.shape[1] // 2
    inner = np.s_[2:-2]  # away from the halves' meeting line
    for picture in (cycles, whitted):
        np.testing.assert_allclose(picture[inner, 2 : half - 2].reshape(-1, 3),
                                   np.tile(by_mirror, ((cycles.shape[0] - 4) * (half - 4), 1)),
                                   atol=CLOSE)  # fmt: skip
        np.testing.assert_allclose(picture[inner, half + 2 : -2].reshape(-1, 3),
                                   np.tile(direct, ((cycles.shape[0] - 4) * (half - 4), 1)),
                                   atol=CLOSE)  # fmt: skip
