"""Tangent-space normal maps as Cycles shades them, side by side with Cycles
(tests/support/cycles.py): a low-poly smooth UV sphere (24 x 12, as assets are) whose Diffuse
BSDF takes its Normal from a Normal Map of a constant tilt along the tangent, in the sun.
Three things Cycles does that Whitted now does too: the tangent is the mesh's MikkTSpace
one interpolated over each triangle (not the triangle's own UV gradient); the normal is
bent back above the surface for the specular closures only, the diffuse keeping the mapped
one (core.kernels.bent_normal); and the diffuse is weighed by the shadow terminator term
where the mapped normal faces a light the smooth one faces away from.

Measured over the 2 x 2 blocks lit above a quarter of the brightest (the rim's blocks
straddle the silhouette, where Cycles' 0.01-pixel samples and Whitted's pixel centre see
different sides): 0.36 of the brightest before, in Blender 4.2; now 0.004. Cycles 4.5 changed
its terminator rule to Conty Estevez, Lecocq and Stein's microfacet shadowing of the bump
(blender_addon.compat.BUMP_TERMINATOR, core.kernels.bent_normal): 0.125 off at the rim
without it, 0.004 with it in 4.5 and 5.2. The test is skipped in Blender 3.4, whose Cycles
bends the diffuse's normal too (0.35 off, measured).

Material › Settings › Bump Map Correction off leaves the softening out in both renderers
(from 4.5 the side test stays): the rim then matches Cycles' darker one as well."""

import numpy as np
import pytest

from tests.support.cycles import add_light, block_means, new_scene, side_by_side, turned

pytestmark = pytest.mark.bpy

TOLERANCE = 0.04  # of the brightest 2 x 2 block
LIT = 0.25  # the blocks measured: lit above this share of the brightest


def _low_poly_ball(bpy, scene, material):
    import bmesh

    mesh = bpy.data.meshes.new("Ball")
    shape = bmesh.new()
    shape.loops.layers.uv.new("UVMap")  # (create_uvsphere fills a UV layer, makes none)
    bmesh.ops.create_uvsphere(shape, u_segments=24, v_segments=12, radius=3.5, calc_uvs=True)
    shape.to_mesh(mesh)
    shape.free()
    for polygon in mesh.polygons:
        polygon.use_smooth = True
    mesh.materials.append(material)
    ball = bpy.data.objects.new("Ball", mesh)
    scene.collection.objects.link(ball)
    ball.rotation_euler = turned(20.0, 0.0, 30.0)  # tangents at a slant to the view
    return ball


def _tilted_diffuse(bpy, in_group):
    """A Diffuse BSDF whose Normal is a Normal Map of colour (0.8, 0.45, 0.85): tilted
    along the tangent and a little against the bitangent; the map inside a node group if
    `in_group` (as asset packs nest them)."""
    material = bpy.data.materials.new("Tilted")
    material.use_nodes = True
    tree = material.node_tree
    tree.nodes.clear()
    diffuse = tree.nodes.new("ShaderNodeBsdfDiffuse")
    diffuse.inputs["Color"].default_value = (0.8, 0.8, 0.8, 1.0)
    host = tree
    if in_group:
        group = bpy.data.node_groups.new("Tilt", "ShaderNodeTree")
        if hasattr(group, "interface"):
            group.interface.new_socket("Normal", in_out="OUTPUT", socket_type="NodeSocketVector")
        else:
            group.outputs.new("NodeSocketVector", "Normal")
        host = group
    mapped = host.nodes.new("ShaderNodeNormalMap")
    mapped.inputs["Color"].default_value = (0.8, 0.45, 0.85, 1.0)
    if in_group:
        out = host.nodes.new("NodeGroupOutput")
        host.links.new(mapped.outputs["Normal"], out.inputs[0])
        node = tree.nodes.new("ShaderNodeGroup")
        node.node_tree = host
        tree.links.new(node.outputs[0], diffuse.inputs["Normal"])
    else:
        tree.links.new(mapped.outputs["Normal"], diffuse.inputs["Normal"])
    output = tree.nodes.new("ShaderNodeOutputMaterial")
    tree.links.new(diffuse.outputs[0], output.inputs["Surface"])
    return material


@pytest.mark.parametrize("in_group", [False, True], ids=["map", "map_in_group"])
def test_a_normal_mapped_low_poly_ball_shades_as_in_cycles(bpy_with_whitted, tmp_path, in_group):
    bpy = bpy_with_whitted
    if bpy.app.version < (4, 0, 0):
        pytest.skip("Cycles 3.4 bends the diffuse's mapped normal too, and weighs it by no "
                    "term: the ball is 35% off (measured), a known gap")  # fmt: skip
    scene = new_scene(bpy)
    bpy.data.objects.remove(bpy.data.objects["Plane"])
    _low_poly_ball(bpy, scene, _tilted_diffuse(bpy, in_group))
    add_light(bpy, scene, "SUN", (0.0, 0.0, 5.0), turned(35.0, -20.0), energy=3.0, angle=0.0)
    cycles, whitted = side_by_side(bpy, scene, tmp_path, samples=16)
    error = lit_disagreement(cycles, whitted)
    print(f"{'group' if in_group else 'map'}: {error:.4f}")
    assert cycles.max() > 0.2  # the premise: a lit ball
    assert error < TOLERANCE, error


def lit_disagreement(cycles, whitted, block=2):
    """Over the blocks whose Cycles brightness is above LIT of the brightest, the largest
    |Whitted - Cycles| per channel, over the brightest block's brightest channel."""
    c, w = block_means(cycles, block), block_means(whitted, block)
    brightest = c.max()
    lit = c.max(axis=-1) > LIT * brightest
    return float(np.abs(w - c)[lit].max() / brightest)


def _tilted_by_displacement(bpy):
    """A Diffuse BSDF over a Displacement (Bump Only) of height -0.577 x in object space: a
    30-degree tilt towards +x, which Cycles makes the surface's own normal (no terminator
    term: core.Material.bump_rule "displaced")."""
    material = bpy.data.materials.new("Displaced")
    material.use_nodes = True
    tree = material.node_tree
    tree.nodes.clear()
    diffuse = tree.nodes.new("ShaderNodeBsdfDiffuse")
    diffuse.inputs["Color"].default_value = (0.8, 0.8, 0.8, 1.0)
    coordinates = tree.nodes.new("ShaderNodeTexCoord")
    split = tree.nodes.new("ShaderNodeSeparateXYZ")
    tree.links.new(coordinates.outputs["Object"], split.inputs[0])
    displacement = tree.nodes.new("ShaderNodeDisplacement")
    displacement.inputs["Midlevel"].default_value = 0.0
    displacement.inputs["Scale"].default_value = -0.577
    tree.links.new(split.outputs["X"], displacement.inputs["Height"])
    output = tree.nodes.new("ShaderNodeOutputMaterial")
    tree.links.new(diffuse.outputs[0], output.inputs["Surface"])
    tree.links.new(displacement.outputs[0], output.inputs["Displacement"])
    if hasattr(material, "displacement_method"):
        material.displacement_method = "BUMP"
    else:
        material.cycles.displacement_method = "BUMP"
    return material


def test_bump_map_correction_off_shades_as_in_cycles(bpy_with_whitted, tmp_path):
    """Material › Settings › Bump Map Correction off: no softening (from 4.5 the side test
    stays). The rim then differs from the corrected map's (0.10-0.14 of the brightest, had
    the correction been kept) and matches Cycles'."""
    bpy = bpy_with_whitted
    if bpy.app.version < (4, 0, 0):
        pytest.skip("Cycles 3.4 bends the diffuse's mapped normal too (see above)")
    scene = new_scene(bpy)
    bpy.data.objects.remove(bpy.data.objects["Plane"])
    material = _tilted_diffuse(bpy, in_group=False)
    material.cycles.use_bump_map_correction = False
    _low_poly_ball(bpy, scene, material)
    add_light(bpy, scene, "SUN", (0.0, 0.0, 5.0), turned(35.0, -20.0), energy=3.0, angle=0.0)
    cycles, whitted = side_by_side(bpy, scene, tmp_path, samples=16)
    error = lit_disagreement(cycles, whitted)
    print(f"uncorrected: {error:.4f}")
    assert cycles.max() > 0.2  # the premise: a lit ball
    assert error < TOLERANCE, error


def test_a_displacements_bend_is_the_surfaces_own_normal_as_in_cycles(bpy_with_whitted,
                                                                       tmp_path):  # fmt: skip
    """The plane tilted 30 degrees towards a sun 80 degrees from straight down by its
    Displacement: Cycles lights it by the tilted normal alone, 0.64 of the sun's
    irradiance, where a terminator term would take 21% (Conty's) or 62% (Chiang's) off."""
    import math

    bpy = bpy_with_whitted
    scene = new_scene(bpy)
    plane = bpy.data.objects["Plane"]
    plane.data.materials.clear()
    plane.data.materials.append(_tilted_by_displacement(bpy))
    add_light(bpy, scene, "SUN", (0.0, 0.0, 5.0), (0.0, math.radians(80.0), 0.0), energy=3.0,
              angle=0.0)  # fmt: skip
    cycles, whitted = side_by_side(bpy, scene, tmp_path, samples=16)
    expected = 0.8 * 3.0 * math.cos(math.radians(50.0)) / math.pi
    print(f"displaced: Cycles {cycles.mean():.4f}, Whitted {whitted.mean():.4f}, "
          f"closed form {expected:.4f}")  # fmt: skip
    np.testing.assert_allclose(cycles.mean(axis=(0, 1)), expected, rtol=0.01)  # the premise
    np.testing.assert_allclose(whitted, cycles, rtol=0.01)
