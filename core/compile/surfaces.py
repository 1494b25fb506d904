"""How each row's surface is shaded (`Surfaces`): its material's row, and for meshes the
smooth flags, vertex normals and UVs per triangle slot."""

from __future__ import annotations

import numpy as np

from ..kernels.layout import Surfaces
from .arrays import concatenated
from .meshes import MeshTables


def pack_surfaces(shapes: list, material_of: dict, meshes: MeshTables) -> Surfaces:
    return Surfaces(
        shape_material=np.array([material_of[id(s.material)] for s in shapes], np.int32),
        mesh_tri_offset=np.array(meshes.tri_offset, np.int64),
        mesh_normal_offset=np.array(meshes.normal_offset, np.int64),
        mesh_uv_offset=np.array(meshes.uv_offset, np.int64),
        tri_smooth=concatenated(meshes.tri_smooth, (0,), np.uint8),
        tri_normal_index=concatenated(meshes.tri_normal_index, (0, 3), np.int32),
        normals=concatenated(meshes.normals, (0, 3), np.float32),
        tri_uv_index=concatenated(meshes.tri_uv_index, (0, 3), np.int32),
        uvs=concatenated(meshes.uvs, (0, 2), np.float32),
    )
