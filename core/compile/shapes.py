"""The shape table and the top-level BVH over it (`Geometry`), with the mesh and CSG arrays
the rows point into.

Rows are the scene's shapes, then the operands of its CSG trees (`csg.pack_csg`). Each row
holds its kind, its inverse transform (the kernels intersect in object space), its world
box, what a shadow ray lets through, and an index into the mesh or CSG tables.
"""

from __future__ import annotations

import numpy as np

from ..checks import MAX_EXTENT
from ..errors import SceneError
from ..kernels.bvh_build import build_bvh
from ..kernels.bvh_wide import WIDTH
from ..kernels.layout import Geometry
from ..kernels.shadow_log import SHADOW_VARIES
from ..kernels.triangles import LEAF_WIDTH
from ..model import Csg, Mesh, Torus
from .arrays import concatenated
from .csg import CsgTables, csg_world_box
from .meshes import MeshTables, has_triangles

# Top-level leaves: shapes per leaf, and the node-visit cost relative to one shape test
_TOP_MAX_LEAF = 2
_TOP_TRAVERSAL_COST = 1.0


def pack_geometry(scene_shapes: list, shapes: list, world_from_object: np.ndarray,
                  csg: CsgTables, tree_of_row: dict, meshes: MeshTables,
                  mesh_of: dict, shadow_share: np.ndarray,
                  shadow_power: np.ndarray) -> Geometry:  # fmt: skip
    """`shapes` are the rows (scene shapes, then CSG operands), placed by world_from_object
    (n, 4, 4); tree_of_row and mesh_of index the CSG and mesh tables; shadow_share[i] is what
    one crossing of row i's surface lets through (`materials.shadow_shares`), and
    shadow_power[i] its colour (`materials.shadow_powers`)."""
    n = len(shapes)
    param = np.zeros((n, 2))
    shape_index = np.full(n, -1, np.int32)
    box_lo, box_hi = np.full((n, 3), -1.0), np.full((n, 3), 1.0)  # object-space boxes
    for i, shape in enumerate(shapes):
        if isinstance(shape, Csg):
            shape_index[i] = tree_of_row[i]
        elif isinstance(shape, Torus):
            param[i] = shape.major_radius, shape.minor_radius
            reach = shape.major_radius + shape.minor_radius
            box_hi[i] = reach, reach, shape.minor_radius
            box_lo[i] = -box_hi[i]
        elif isinstance(shape, Mesh):
            m = mesh_of[id(shape.mesh)]
            shape_index[i] = m
            box_lo[i], box_hi[i] = meshes.lo[m], meshes.hi[m]
    object_from_world = np.linalg.inv(world_from_object)[:, :3] if n else np.empty((0, 3, 4))
    with np.errstate(over="ignore", invalid="ignore"):  # a shape too large: named next
        lo, hi = _world_boxes(world_from_object, box_lo, box_hi)
    _check_reach(shapes, lo, hi)
    for i, tree in tree_of_row.items():
        lo[i], hi[i] = csg_world_box(csg.program, *csg.ranges[tree], lo, hi)
    # Only the scene's own shapes enter the top level (CSG operands are reached through
    # their tree); meshes left without triangles (all degenerate) and CSG solids whose
    # operands' boxes do not overlap have nothing to hit: leave them out
    scene_rows = len(scene_shapes)
    solid = np.array(
        [i < scene_rows and np.all(lo[i] <= hi[i]) and (
            not isinstance(s, Mesh) or len(meshes.lo) and has_triangles(meshes, mesh_of[id(s.mesh)])
        ) for i, s in enumerate(shapes)], bool
    ).reshape(-1)  # fmt: skip
    if solid.any():
        top_lo, top_hi, top_info, top_order = build_bvh(
            lo[solid], hi[solid], _TOP_MAX_LEAF, _TOP_TRAVERSAL_COST
        )
        top_order = np.flatnonzero(solid)[top_order]
    else:
        # Nothing to hit: an empty box and no node, as the builder would make, without a
        # kernel (the warm-up packs an empty scene for the kernels' argument types alone)
        top_lo, top_hi = np.zeros((1, 3)), np.full((1, 3), -1.0)
        top_info, top_order = np.zeros((0, 2), np.int32), np.zeros(0, np.int32)
    tau = _shadow_transparency(shapes, scene_rows, shadow_share)
    return Geometry(
        top_bounds=np.ascontiguousarray(np.hstack([top_lo, top_hi])),
        top_info=np.ascontiguousarray(top_info, np.int32),
        top_order=np.ascontiguousarray(top_order, np.int32),
        shape_kind=np.array([s.kernel_kind for s in shapes], np.int32),
        shape_object_from_world=object_from_world,
        shape_param=param,
        shape_index=shape_index,
        shape_transparency=tau,
        shape_shadow_power=_shadow_power(tau, shadow_power),
        shape_bounds=np.ascontiguousarray(np.hstack([lo, hi]).reshape(n, 6)),
        mesh_root=np.array(meshes.root, np.int32),
        node_boxes=concatenated(meshes.node_boxes, (0, 6, WIDTH), np.float32),
        node_links=concatenated(meshes.node_links, (0, WIDTH), np.int32),
        tri_corners=concatenated(meshes.tri_corners, (0, 9, LEAF_WIDTH), np.float32),
        csg_range=np.array(csg.ranges, np.int32).reshape(-1, 2),
        csg_program=np.array(csg.program, np.int32),
    )


def _shadow_transparency(shapes: list, scene_rows: int, shadow_share: list) -> np.ndarray:
    """What each row lets through per surface crossed by a shadow ray: its material's share
    (shadow_share); 1 for a scene shape that casts no shadow (kernels skip such rows, which
    is exact: 1^crossings = 1); for a CSG row 0, as its operands' rows decide."""
    tau = np.empty(len(shapes))
    for i, shape in enumerate(shapes):
        if i < scene_rows and not shape.casts_shadows:
            tau[i] = 1.0
        else:
            tau[i] = 0.0 if isinstance(shape, Csg) else shadow_share[i]
    return tau


def _shadow_power(tau: np.ndarray, shadow_power: np.ndarray) -> np.ndarray:
    """Geometry.shape_shadow_power: each row's colour where it lets some light through; no
    rows at all where no shadow can be coloured (no coloured share, no share that varies
    over a surface), which the kernels read as "grey everywhere" and skip: the colour's
    bookkeeping is then not done at all."""
    power = np.where(((tau > 0.0) & (tau < 1.0))[:, None], shadow_power, 1.0)
    if np.all(power == 1.0) and not np.any(tau == SHADOW_VARIES):
        return np.ones((0, 3))
    return power


def _check_reach(shapes: list, lo: np.ndarray, hi: np.ndarray) -> None:
    """Refuse a shape reaching past MAX_EXTENT from the origin, by name: drawn in its own
    space, scaled by the inverse of its size, it would vanish or fill the frame wrongly."""
    with np.errstate(invalid="ignore"):
        reach = np.maximum(np.abs(lo), np.abs(hi)).max(axis=1, initial=0.0)
        empty = np.any(lo > hi, axis=1)  # a mesh left without triangles
        bad = np.flatnonzero(~empty & ~(reach <= MAX_EXTENT))
    if len(bad):
        shape = shapes[bad[0]]
        raise SceneError(
            shape.owner,
            "transform",
            f"reaches {reach[bad[0]]:.3g} scene units from the origin (its size and place); "
            f"Whitted renders shapes within {MAX_EXTENT:g} of it: scale the scene down",
        )


def _world_boxes(world_from_object, lo, hi):
    """World boxes (n, 3) around the object boxes lo..hi under each transform, padded
    against rounding."""
    corner_of = np.array(np.meshgrid([0, 1], [0, 1], [0, 1], indexing="ij")).reshape(3, 8).T
    corners = np.where(corner_of[None, :, :] == 1, hi[:, None, :], lo[:, None, :])  # (n, 8, 3)
    world = np.einsum("nij,nkj->nki", world_from_object[:, :3, :3], corners)
    world += world_from_object[:, None, :3, 3]
    w_lo, w_hi = world.min(axis=1), world.max(axis=1)
    pad = 1e-12 * (np.abs(w_lo).max(axis=1) + np.abs(w_hi).max(axis=1))[:, None]
    return w_lo - pad, w_hi + pad
