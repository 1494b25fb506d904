"""Blender meshes into `core.TriangleMesh`, through `foreach_get` into numpy (no Python loop
over triangles), with per-face smooth flags, Blender's corner (split) normals and the
active UV map. Each distinct evaluated mesh is converted once per render and shared by every
object instance that uses it."""

from __future__ import annotations

import numpy as np

import core

from .compat import prepare_corner_normals


def triangle_mesh(mesh, name: str) -> core.TriangleMesh:
    """The triangles of a Blender mesh (object space)."""
    mesh.calc_loop_triangles()
    prepare_corner_normals(mesh)
    triangles_blender = mesh.loop_triangles
    count = len(triangles_blender)
    vertices = np.empty(len(mesh.vertices) * 3, np.float32)
    mesh.vertices.foreach_get("co", vertices)
    triangles = np.empty(count * 3, np.int32)
    triangles_blender.foreach_get("vertices", triangles)
    smooth = np.empty(count, bool)
    triangles_blender.foreach_get("use_smooth", smooth)
    corner_normals = None
    if smooth.any():
        corner_normals = np.empty(count * 9, np.float32)
        triangles_blender.foreach_get("split_normals", corner_normals)
        corner_normals = corner_normals.reshape(count, 3, 3)
    corner_uvs = None
    uv_layer = mesh.uv_layers.active
    if uv_layer is not None and count:
        loops = np.empty(count * 3, np.int32)
        triangles_blender.foreach_get("loops", loops)
        uvs = np.empty(len(mesh.loops) * 2, np.float32)
        uv_layer.data.foreach_get("uv", uvs)
        corner_uvs = uvs.reshape(-1, 2)[loops].reshape(count, 3, 2)
    return core.TriangleMesh(
        vertices=vertices.reshape(-1, 3),
        triangles=triangles.reshape(-1, 3),
        smooth=smooth,
        corner_normals=corner_normals,
        corner_uvs=corner_uvs,
        name=name,
    )
