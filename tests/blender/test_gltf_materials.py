"""Materials as Blender's glTF importer makes them of the public sample models, side by side
with Cycles (tests/support/cycles.py): small glTF files written here (tests/support/
gltf_files.py) go through `bpy.ops.import_scene.gltf`, in every Blender version the tests
run as a module.

Emissive maps: the importer links the map to the Principled BSDF's Emission Color (through a
Mix node when the emissive factor is coloured; a grey factor goes into Emission Strength).
Until issue 61 the surface rendered black: the map's steps came between the Principled
step and its second row, which it then missed (core.compile.shader_program)."""

import numpy as np
import pytest

from tests.blender.test_cycles_glints import disagreement
from tests.support.cycles import add_light, new_scene, side_by_side, turned
from tests.support.gltf_files import checker, import_gltf, write_quad

pytestmark = pytest.mark.bpy

# A pixel agrees when within this of Cycles' (the emission is exact in both, Cycles' in
# float32); a texel edge through a pixel's centre is Cycles' blend of two texels
CLOSE = 2e-3
EDGE_SHARE = 0.02

BASE = checker((200, 60, 30), (40, 80, 220))
GLOW = checker((0, 0, 0), (255, 200, 50))


@pytest.mark.parametrize("factor", [(1.0, 1.0, 1.0), (0.5, 0.2, 0.1)], ids=["grey", "coloured"])
def test_an_emissive_map_glows_as_in_cycles(bpy_with_whitted, tmp_path, factor):
    """A base colour map and an emissive map, in the dark: the camera sees the emission."""
    bpy = bpy_with_whitted
    scene = new_scene(bpy)
    bpy.data.objects.remove(bpy.data.objects["Plane"])
    material = dict(
        name="Glowing",
        pbrMetallicRoughness=dict(baseColorTexture=dict(index=0), metallicFactor=0.0),
        emissiveTexture=dict(index=1),
        emissiveFactor=list(factor),
    )
    import_gltf(bpy, write_quad(tmp_path / "quad.gltf", material, [BASE, GLOW]))
    tree = bpy.data.materials["Glowing"].node_tree
    emission = next(n for n in tree.nodes if n.type == "BSDF_PRINCIPLED").inputs["Emission Color"]
    assert emission.is_linked  # the importer's shape: the map (or its Mix) feeds it
    cycles, whitted = side_by_side(bpy, scene, tmp_path, samples=16)
    assert cycles.max() > 0.1  # the premise: something glows
    off = np.abs(whitted - cycles).max(axis=-1) > CLOSE
    assert off.mean() <= EDGE_SHARE, (off.mean(), whitted.mean(), cycles.mean())


def test_a_vertex_coloured_model_is_lit_as_in_cycles(bpy_with_whitted, tmp_path):
    """COLOR_0 times the base colour factor, as glTF asks: the importer makes a colour
    attribute and a Color Attribute node multiplied into the Base Color by a Mix node.
    Before issue 61's colour attributes the node was named in a warning and the quad drawn
    in the Mix's other colour."""
    bpy = bpy_with_whitted
    if bpy.app.version < (4, 0, 0):
        pytest.skip("Principled v1's Disney diffuse is drawn as Lambert (3% off)")
    scene = new_scene(bpy)
    bpy.data.objects.remove(bpy.data.objects["Plane"])
    material = dict(name="Painted", pbrMetallicRoughness=dict(
        baseColorFactor=[0.9, 0.8, 0.7, 1.0], metallicFactor=0.0, roughnessFactor=0.5))  # fmt: skip
    corners = [
        [1.0, 0.1, 0.1, 1.0],
        [0.1, 1.0, 0.1, 1.0],
        [0.1, 0.1, 1.0, 1.0],
        [1.0, 1.0, 0.1, 1.0],
    ]
    # past the picture's edges (Cycles 4.5 and 5.0 catch a few samples of a nearby edge)
    import_gltf(bpy, write_quad(tmp_path / "painted.gltf", material, [], 4.5, corners))
    tree = bpy.data.materials["Painted"].node_tree
    assert any(n.type == "VERTEX_COLOR" for n in tree.nodes)  # the importer's shape
    add_light(bpy, scene, "SUN", (0.0, 0.0, 5.0), turned(20.0, 10.0), energy=3.0, angle=0.0)
    cycles, whitted = side_by_side(bpy, scene, tmp_path, samples=16)
    error = disagreement(cycles, whitted)
    print(f"vertex-coloured glTF quad: {error:.4f}")
    assert np.ptp(cycles[..., 0]) > 0.1  # the premise: the colours vary over the quad
    assert error < 0.03, error


def test_an_emissive_map_lights_the_scene_as_in_cycles(bpy_with_whitted, tmp_path):
    """The emissive map of a quad hidden from the camera lights the white plane below in its
    cells' colours, as Cycles' mesh light does (diffuse bounces 0: its direct light). Before
    issue 61's textured emission lighting, the quad lit nothing: "seen, but not lighting
    the scene", and the plane was black."""
    bpy = bpy_with_whitted
    scene = new_scene(bpy)
    material = dict(
        name="Lamp",
        pbrMetallicRoughness=dict(baseColorFactor=[0.0, 0.0, 0.0, 1.0], metallicFactor=0.0),
        emissiveTexture=dict(index=0),
        emissiveFactor=[1.0, 1.0, 1.0],
    )
    warm_and_cool = checker((255, 90, 20), (20, 110, 255))
    import_gltf(bpy, write_quad(tmp_path / "lamp.gltf", material, [warm_and_cool], 1.6))
    lamp = bpy.data.objects["Quad"]
    lamp.location, lamp.rotation_euler = (0.4, -0.3, 1.3), turned(0.0, 0.0, 25.0)
    lamp.visible_camera = False
    # each of Whitted's samples is one sub-triangle's colour: more of them than a constant
    # panel needs (core.kernels.light_mesh); Cycles' noise at 4096 as for its mesh lights
    scene.whitted.shadow_samples = 1024
    cycles, whitted = side_by_side(bpy, scene, tmp_path, samples=4096)
    # 4 x 4 blocks: both renderers' noise averaged down (measured 0.028 in 2 x 2 blocks, the
    # dim corners' noise; the mean over the plane within 0.1% in every channel)
    error = disagreement(cycles, whitted, block=4)
    print(f"emissive map lighting the plane: {error:.4f}")
    assert cycles.max() > 0.05  # the premise: the plane is lit
    # both colours show on the plane, side by side
    red_over_blue = whitted[..., 0] / np.maximum(whitted[..., 2], 1e-6)
    assert red_over_blue.max() > 1.5 and red_over_blue.min() < 1 / 1.5
    assert error < 0.03, error
