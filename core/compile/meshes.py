"""Triangle meshes into flat arrays: degenerate triangles dropped, normals, UVs, BVH.

Each distinct `TriangleMesh` is packed once, however many `Mesh` shapes use it. Its triangles
are stored in the BVH's leaf blocks (four slots a leaf, see `core.kernels.triangles`), so that
a leaf names one block and no permutation array is needed at render time. Everything kept per
triangle (smooth flags, normal and UV rows) is kept per slot; a slot a leaf leaves empty
repeats one of the leaf's triangles there and NaN corners, so it is never hit.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ..kernels.attributes import EDGE_DISTANCES
from ..kernels.bvh_build import build_bvh
from ..kernels.bvh_collapse import collapse_to_wide
from ..kernels.bvh_wide import LEAF_COUNT_BITS, number_leaf_blocks, offset_links
from ..kernels.triangles import LEAF_WIDTH
from ..model import Mesh, TriangleMesh
from ..model.shader import EDGE_ATTRIBUTE, TANGENT_ATTRIBUTE

# Leaves of up to MESH_MAX_LEAF triangles; a node visit costs about as much as this many
# triangle tests. Chosen on the million-triangle benchmark mesh with the four-wide BVH, all
# variants timed in one process (best of 4), as (leaf, cost): primary, incoherent, shadow
# Mrays/s per core, bytes per triangle: (4, 3) 5.07, 1.05, 2.24, 53; (4, 2) 5.03, 1.01, 2.29,
# 61; (4, 1) 5.02, 1.02, 2.21, 69; (2, 1) 4.81, 0.99, 2.22, 69; (6, 3) 4.88, 1.03, 2.17, 49.
# Checked again with the eight-wide tree collapsed at least node area: against cost 3, cost
# 1.5 traced 14% slower (primary and incoherent), 2 9-11% slower, 4 the same within 2%.
# A leaf is one block of LEAF_WIDTH slots, so no leaf may hold more.
MESH_MAX_LEAF = 4
assert MESH_MAX_LEAF <= LEAF_WIDTH and MESH_MAX_LEAF < 1 << LEAF_COUNT_BITS
MESH_TRAVERSAL_COST = 3.0


@dataclass
class MeshTables:
    """The concatenation of every packed mesh (see `PackedScene` for the fields)."""

    root: list = field(default_factory=list)
    tri_offset: list = field(default_factory=list)
    normal_offset: list = field(default_factory=list)
    uv_offset: list = field(default_factory=list)
    lo: list = field(default_factory=list)  # object-space bounds per mesh
    hi: list = field(default_factory=list)
    node_boxes: list = field(default_factory=list)  # (n, 6, 8) float32, see bvh_wide
    node_links: list = field(default_factory=list)  # (n, 8) int32, global
    tri_corners: list = field(default_factory=list)  # (blocks, 9, 4) float32, see triangles
    tri_smooth: list = field(default_factory=list)
    tri_normal_index: list = field(default_factory=list)
    normals: list = field(default_factory=list)
    tri_uv_index: list = field(default_factory=list)
    uvs: list = field(default_factory=list)
    # the colour attributes the programs read (core.kernels.attributes), each mesh's rows
    # of them (-1: it lacks one), and those rows
    attribute_names: list = field(default_factory=list)
    color_offset: list = field(default_factory=list)
    tri_color_index: list = field(default_factory=list)
    colors: list = field(default_factory=list)
    color_rows: int = 0
    color_entries: int = 0
    # nodes, triangles, and triangle slots (four a leaf block, some empty)
    counts: dict = field(default_factory=lambda: {"nodes": 0, "tris": 0, "slots": 0})
    normal_rows: int = 0
    uv_rows: int = 0
    normal_entries: int = 0
    uv_entries: int = 0
    dropped: dict = field(default_factory=dict)  # mesh name -> degenerate triangles dropped


def vertex_normals_from_faces(vertices: np.ndarray, triangles: np.ndarray) -> np.ndarray:
    """Area-weighted average of the face normals around each vertex (the report's way)."""
    v = vertices.astype(np.float64)
    face = np.cross(
        v[triangles[:, 1]] - v[triangles[:, 0]], v[triangles[:, 2]] - v[triangles[:, 0]]
    )
    normals = np.empty_like(v)
    for axis in range(3):
        normals[:, axis] = np.bincount(
            triangles.ravel(), weights=np.repeat(face[:, axis], 3), minlength=len(v)
        )
    length = np.linalg.norm(normals, axis=1, keepdims=True)
    return normals / np.where(length > 0.0, length, 1.0)


def add_mesh(tables: MeshTables, mesh: TriangleMesh) -> int:
    """Pack `mesh` into `tables`; returns its mesh index."""
    index = len(tables.root)
    vertices = np.ascontiguousarray(mesh.vertices, np.float32)
    triangles = np.asarray(mesh.triangles, np.int64)
    exact = vertices.astype(np.float64)
    v0, v1, v2 = (exact[triangles[:, k]] for k in range(3))
    area2 = np.linalg.norm(np.cross(v1 - v0, v2 - v0), axis=1)
    keep = np.flatnonzero(area2 > 0.0)
    if len(keep) < len(triangles):
        tables.dropped[mesh.name] = len(triangles) - len(keep)

    lo = np.minimum(np.minimum(v0, v1), v2)[keep]
    hi = np.maximum(np.maximum(v0, v1), v2)[keep]
    node_lo, node_hi, node_info, order = build_bvh(lo, hi, MESH_MAX_LEAF, MESH_TRAVERSAL_COST)
    source = keep[order]  # original triangle of each leaf-ordered triangle

    base_node, base_slot = tables.counts["nodes"], tables.counts["slots"]
    # Boxes one float32 step larger than their triangles: the watertight triangle test may
    # claim a ray that passes a hair outside a triangle at a shared vertex or edge (so that
    # exactly one neighbour claims it), and that triangle's box must not have culled it
    padded_lo = np.nextafter(node_lo.astype(np.float32), np.float32(-np.inf))
    padded_hi = np.nextafter(node_hi.astype(np.float32), np.float32(np.inf))
    boxes, links = collapse_to_wide(padded_lo, padded_hi, node_info)
    links, block_first, block_count = number_leaf_blocks(links)
    # The source triangle of every slot; an empty slot repeats its leaf's first triangle
    lane = np.arange(LEAF_WIDTH)
    filled = lane < block_count[:, None]
    leaf_ordered = np.where(filled, block_first[:, None] + lane, block_first[:, None])
    slot_source = source[leaf_ordered].ravel()
    corners = vertices[triangles[slot_source]].reshape(len(block_first), LEAF_WIDTH, 9)
    corners[~filled] = np.nan
    tables.node_boxes.append(boxes)
    tables.node_links.append(offset_links(links, base_node, base_slot // LEAF_WIDTH))
    tables.tri_corners.append(np.ascontiguousarray(corners.transpose(0, 2, 1)))
    smooth = np.broadcast_to(np.asarray(mesh.smooth, bool), (len(triangles),))[slot_source]
    tables.tri_smooth.append(smooth.astype(np.uint8))
    tables.root.append(base_node)
    tables.tri_offset.append(base_slot)
    tables.lo.append(node_lo[0] if len(keep) else np.zeros(3))
    tables.hi.append(node_hi[0] if len(keep) else np.zeros(3))

    tables.normal_offset.append(_add_normals(tables, mesh, triangles, slot_source, smooth))
    tables.uv_offset.append(_add_uvs(tables, mesh, triangles, slot_source))
    tables.color_offset.append(
        [_add_colors(tables, mesh, slot_source, name) for name in tables.attribute_names]
    )
    tables.counts["nodes"] += len(links)
    tables.counts["tris"] += len(source)
    tables.counts["slots"] += len(slot_source)
    return index


def _add_normals(tables, mesh, triangles, source, smooth) -> int:
    if not smooth.any():
        return -1
    if mesh.corner_normals is not None:
        table = np.asarray(mesh.corner_normals, np.float32).reshape(-1, 3)
        index = 3 * source[:, None] + np.arange(3)
    else:
        given = mesh.vertex_normals
        if given is None:
            given = vertex_normals_from_faces(np.asarray(mesh.vertices, np.float64), triangles)
        table = np.asarray(given, np.float32)
        index = triangles[source]
    offset = tables.normal_rows
    tables.tri_normal_index.append((index + tables.normal_entries).astype(np.int32))
    tables.normals.append(table)
    tables.normal_rows += len(index)
    tables.normal_entries += len(table)
    return offset


def _add_uvs(tables, mesh, triangles, source) -> int:
    if mesh.corner_uvs is not None:
        table = np.asarray(mesh.corner_uvs, np.float32).reshape(-1, 2)
        index = 3 * source[:, None] + np.arange(3)
    elif mesh.vertex_uvs is not None:
        table = np.asarray(mesh.vertex_uvs, np.float32)
        index = triangles[source]
    else:
        return -1
    offset = tables.uv_rows
    tables.tri_uv_index.append((index + tables.uv_entries).astype(np.int32))
    tables.uvs.append(table)
    tables.uv_rows += len(index)
    tables.uv_entries += len(table)
    return offset


def _add_colors(tables, mesh, source, name: str) -> int:
    """The mesh's colour attribute `name` ("": its default one) for its triangle slots;
    its first row, or -1 if it has none of that name."""
    if name == EDGE_ATTRIBUTE:  # computed at the hit from the triangle's corners
        return EDGE_DISTANCES
    colors = mesh.corner_colors or {}
    if name == TANGENT_ATTRIBUTE:  # (a tangent-space Normal Map's)
        colors = {} if mesh.corner_tangents is None else {name: mesh.corner_tangents}
    key = name or mesh.default_color
    if key not in colors:
        return -1
    table = np.asarray(colors[key], np.float32).reshape(-1, 4)
    index = 3 * source[:, None] + np.arange(3)
    offset = tables.color_rows
    tables.tri_color_index.append((index + tables.color_entries).astype(np.int32))
    tables.colors.append(table)
    tables.color_rows += len(index)
    tables.color_entries += len(table)
    return offset


def pack_meshes(shapes: list, attribute_names=()) -> tuple[MeshTables, dict[int, int]]:
    """Every distinct `TriangleMesh` of these shapes, once; each one's index by id();
    with the colour attributes named (core.model.shader.attribute_names)."""
    tables, index = MeshTables(attribute_names=list(attribute_names)), {}
    for shape in shapes:
        if isinstance(shape, Mesh) and id(shape.mesh) not in index:
            index[id(shape.mesh)] = add_mesh(tables, shape.mesh)
    return tables, index


def has_triangles(tables: MeshTables, mesh: int) -> bool:
    """Whether packed mesh `mesh` kept any triangle (degenerate ones are dropped)."""
    following = mesh + 1 < len(tables.tri_offset)
    end = tables.tri_offset[mesh + 1] if following else tables.counts["slots"]
    return end > tables.tri_offset[mesh]
