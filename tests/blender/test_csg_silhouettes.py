"""CSG silhouettes against an independent implementation: Blender's own mesh Boolean.

The project report's three CSG examples are built twice: as exact `Csg` trees of analytic
shapes, and by Blender's Boolean modifier on finely tessellated meshes of the same solids.
Both are seen by the same camera rays; their masks must overlap with IoU >= 0.995. (The
tessellation alone, 128 segments, moves a silhouette by under 3e-4 of the radius.)
"""

import numpy as np
import pytest

from core import Mesh, TriangleMesh
from tests.blender.conftest import clear_scene
from tests.support.csg_examples import EXAMPLES, analytic_tree
from tests.support.probe import hits, packed_shapes
from tests.support.rays import rays_towards_origin

pytestmark = pytest.mark.bpy

SEGMENTS = 128
BLENDER_OPERATION = {"intersection": "INTERSECT", "union": "UNION", "difference": "DIFFERENCE"}


def blender_object(bpy, kind, matrix):
    from mathutils import Matrix

    if kind == "sphere":
        bpy.ops.mesh.primitive_uv_sphere_add(segments=SEGMENTS, ring_count=SEGMENTS // 2)
    elif kind == "cube":
        bpy.ops.mesh.primitive_cube_add(size=2.0)
    else:
        bpy.ops.mesh.primitive_cylinder_add(vertices=SEGMENTS, radius=1.0, depth=2.0)
    obj = bpy.context.active_object
    obj.matrix_world = Matrix(matrix.tolist())
    return obj


def blender_boolean_mesh(bpy, first, steps):
    """The solid made by Blender's Boolean modifiers, as world-space triangles."""
    clear_scene(bpy)
    base = blender_object(bpy, *first)
    for operation, operand in steps:
        cutter = blender_object(bpy, *operand)
        modifier = base.modifiers.new(operation, "BOOLEAN")
        modifier.operation = BLENDER_OPERATION[operation]
        modifier.object = cutter
        cutter.hide_set(True)
    depsgraph = bpy.context.evaluated_depsgraph_get()
    evaluated = base.evaluated_get(depsgraph)
    mesh = evaluated.to_mesh()
    mesh.calc_loop_triangles()
    vertices = np.empty(len(mesh.vertices) * 3)
    mesh.vertices.foreach_get("co", vertices)
    triangles = np.empty(len(mesh.loop_triangles) * 3, np.int64)
    mesh.loop_triangles.foreach_get("vertices", triangles)
    world = np.array(base.matrix_world)
    vertices = vertices.reshape(-1, 3) @ world[:3, :3].T + world[:3, 3]
    evaluated.to_mesh_clear()
    return TriangleMesh(vertices, triangles.reshape(-1, 3))


def camera_rays():
    # Nearly along the cube-minus-cylinder hole (the y axis), so the background shows through
    return rays_towards_origin((1.2, -5.0, 1.5), 160, 0.3)


@pytest.mark.parametrize(("name", "first", "steps"), EXAMPLES, ids=[e[0] for e in EXAMPLES])
def test_silhouette_matches_blenders_mesh_boolean(bpy_with_whitted, name, first, steps):
    origins, directions = camera_rays()
    _, analytic_row, _ = hits(packed_shapes(analytic_tree(first, steps)), origins, directions)
    mesh = blender_boolean_mesh(bpy_with_whitted, first, steps)
    _, mesh_row, _ = hits(packed_shapes(Mesh(name, mesh=mesh)), origins, directions)
    ours, theirs = analytic_row >= 0, mesh_row >= 0
    iou = np.count_nonzero(ours & theirs) / np.count_nonzero(ours | theirs)
    assert np.count_nonzero(ours) > 0.1 * len(ours)
    print(f"{name}: IoU {iou:.5f}")
    assert iou >= 0.995, f"{name}: IoU {iou:.5f}"
