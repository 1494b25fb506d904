"""How each row's surface is shaded (`Surfaces`): its material's row, and for meshes the
smooth flags, vertex normals and UVs per triangle slot; what the passes say of its object
(pass index, holdout, Cryptomatte id, the rays that see it), taken from the scene shape
the row belongs to."""

from __future__ import annotations

import numpy as np

from ..kernels.layout import VISIBLE_CAMERA, VISIBLE_GLOSSY, VISIBLE_TRANSMISSION, Surfaces
from ..model.shapes import Mesh, Torus
from ..passes import crypto_id
from .arrays import concatenated
from .meshes import MeshTables


def pack_surfaces(shapes: list, owners: list, material_of: dict, meshes: MeshTables) -> Surfaces:
    """`owners[i]` is the scene shape row i belongs to (a CSG operand's top node)."""
    ids = {}  # each name hashed once: instances share their object's name
    for owner in owners:
        if owner.name not in ids:
            ids[owner.name] = crypto_id(owner.name)
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
        mesh_color_offset=np.array(meshes.color_offset, np.int64).reshape(
            len(meshes.root), len(meshes.attribute_names)
        ),
        tri_color_index=concatenated(meshes.tri_color_index, (0, 3), np.int32),
        colors=concatenated(meshes.colors, (0, 4), np.float32),
        shape_pass_index=np.array([o.pass_index for o in owners], np.int32),
        shape_holdout=np.array([o.holdout for o in owners], np.uint8),
        shape_crypto=np.array([ids[o.name] for o in owners], np.float32),
        shape_visibility=np.array([_visibility(o) for o in owners], np.uint8),
        shape_texspace=np.array([_texture_space(s) for s in shapes], float).reshape(-1, 6),
    )


def _texture_space(shape) -> tuple:
    """(centre xyz, half size xyz) of the shape's texture space: its own, or its box, with
    Blender's guard against flat boxes (a zero size becomes 1, a tiny one 1e-5)."""
    if shape.texture_space is not None:
        centre, half = (np.asarray(v, float) for v in shape.texture_space)
    else:
        lo, hi = _object_box(shape)
        centre, half = (lo + hi) / 2.0, (hi - lo) / 2.0
    half = np.where(half == 0.0, 1.0, np.where(np.abs(half) < 1e-5, 1e-5, half))
    return (*centre, *half)


def _object_box(shape) -> tuple:
    if isinstance(shape, Mesh) and len(shape.mesh.vertices):
        vertices = np.asarray(shape.mesh.vertices, float)
        return vertices.min(axis=0), vertices.max(axis=0)
    if isinstance(shape, Torus):
        reach = shape.major_radius + shape.minor_radius
        return (np.array([-reach, -reach, -shape.minor_radius]),
                np.array([reach, reach, shape.minor_radius]))  # fmt: skip
    return -np.ones(3), np.ones(3)  # the canonical shapes fill [-1, 1]^3


def _visibility(shape) -> int:
    return (
        VISIBLE_CAMERA * shape.seen_by_camera
        + VISIBLE_GLOSSY * shape.seen_in_mirrors
        + VISIBLE_TRANSMISSION * shape.seen_through_glass
    )
