"""A smooth metal with a normal map, side by side with Cycles (tests/support/cycles.py):
where the map bends the normal so far from the viewer that the mirror direction about it
points into the surface, Cycles tilts the normal back just enough (core.kernels.bent_normal)
and the metal shows the World there. Before issue 61 Whitted drew such texels dark (black
crescents on a normal-mapped metal ball's rim)."""

import math

import numpy as np
import pytest

from tests.support.cycles import new_scene, normal_map_image, side_by_side, uniform_world

pytestmark = pytest.mark.bpy


def _normal_mapped_metal(bpy):
    """Principled metal, roughness 0, its normal from a 4 x 4 map of strongly tilted texel
    normals (tangent space, Closest, strength 1)."""
    image = normal_map_image(bpy, "Dents", seed=61, across=(0.1, 0.9), up=(0.6, 0.9))
    material = bpy.data.materials.new("Dented metal")
    material.use_nodes = True
    tree = material.node_tree
    principled = next(n for n in tree.nodes if n.type == "BSDF_PRINCIPLED")
    principled.inputs["Base Color"].default_value = (0.95, 0.7, 0.4, 1.0)
    principled.inputs["Metallic"].default_value = 1.0
    principled.inputs["Roughness"].default_value = 0.0
    texture = tree.nodes.new("ShaderNodeTexImage")
    texture.image = image
    texture.interpolation = "Closest"
    normal_map = tree.nodes.new("ShaderNodeNormalMap")
    normal_map.inputs["Strength"].default_value = 1.0
    tree.links.new(texture.outputs["Color"], normal_map.inputs["Color"])
    tree.links.new(normal_map.outputs["Normal"], principled.inputs["Normal"])
    return material


def _uv_floor(bpy, scene, material, half=10.0):
    """A square floor 2 half across at z = 0, UVs (0, 0) to (1, 1) over it (its tangents
    follow them)."""
    mesh = bpy.data.meshes.new("Floor")
    mesh.from_pydata([(-half, -half, 0), (half, -half, 0), (half, half, 0), (-half, half, 0)],
                     [], [(0, 1, 2, 3)])  # fmt: skip
    uv = mesh.uv_layers.new(name="UVMap")
    for loop, corner in zip(uv.data, [(0, 0), (1, 0), (1, 1), (0, 1)], strict=True):
        loop.uv = corner
    mesh.materials.append(material)
    scene.collection.objects.link(bpy.data.objects.new("Floor", mesh))


def test_a_normal_mapped_metal_floor_seen_at_a_low_angle_reflects_the_world_as_in_cycles(
    bpy_with_whitted, tmp_path
):
    """Seen 20 degrees above the floor, the texels whose normal the map tilts away from the
    camera would mirror the ray into the floor: Cycles lifts it just above, showing the
    World there, as Whitted now does."""
    bpy = bpy_with_whitted
    scene = new_scene(bpy)
    bpy.data.objects.remove(bpy.data.objects["Plane"])
    uniform_world(scene, (0.6, 0.7, 0.8))
    _uv_floor(bpy, scene, _normal_mapped_metal(bpy))
    camera = scene.camera
    tilt = math.radians(70.0)  # looking down at 20 degrees
    camera.rotation_euler = (tilt, 0.0, 0.0)
    camera.location = (0.0, -10.0 * math.sin(tilt), 10.0 * math.cos(tilt))
    cycles, whitted = side_by_side(bpy, scene, tmp_path, samples=16)
    on_floor = np.abs(cycles - np.array([0.6, 0.7, 0.8])).max(axis=-1) > 1e-3
    dark = (whitted.sum(axis=-1) < 0.5 * cycles.sum(axis=-1)) & on_floor
    off = (np.abs(whitted - cycles).max(axis=-1) > 0.03) & on_floor
    print(f"{dark.mean():.4f} of the pixels dark, {off.mean():.4f} off by 0.03; largest "
          f"{np.abs(whitted - cycles).max():.3f}")  # fmt: skip
    assert on_floor.mean() > 0.3  # the premise: the floor fills much of the view
    assert dark.sum() == 0  # no dark texels: a metal in a bright World is never dark
    assert off.mean() <= 0.05
