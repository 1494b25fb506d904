"""Compile a `Scene` into `PackedScene`: the flat arrays that are all the kernels ever see.

The order is fixed: validate, then camera, materials and textures (shapes refer to them by
index), meshes (each `TriangleMesh` once), shapes, the top-level BVH over the shapes, lights.
Every array has a fixed dtype and rank whatever the scene, so the kernels compile once and
load from the cache for every scene after. Scenes without some feature get empty arrays, and
the kernels do no work for it.
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np

from .csg_packing import CsgTables, add_csg, csg_world_box
from .kernels.bvh_build import build_bvh
from .kernels.bvh_wide import WIDTH
from .kernels.layout import Frame, Geometry, Lights, Materials, PackedScene, Surfaces
from .kernels.options import (
    OPTION_COUNT,
    OPTION_MAX_DEPTH,
    OPTION_PIXEL_PATTERN,
    OPTION_PIXEL_SAMPLES,
    OPTION_SEED,
    OPTION_SHADOW_CULLING,
    OPTION_SHADOW_PATTERN,
    OPTION_SHADOW_SAMPLES,
    PIXEL_PATTERNS,
    SHADOW_PATTERNS,
)
from .kernels.shapes import (
    SHAPE_BOX,
    SHAPE_CONE,
    SHAPE_CSG,
    SHAPE_CYLINDER,
    SHAPE_MESH,
    SHAPE_SPHERE,
    SHAPE_TORUS,
)
from .kernels.triangles import LEAF_WIDTH
from .memory_estimate import check_fits, estimate
from .mesh_packing import MeshTables, add_mesh, concatenated
from .scene import (
    AreaLight,
    Box,
    Cone,
    Csg,
    Cylinder,
    DirectionalLight,
    Mesh,
    PointLight,
    RenderSettings,
    Scene,
    Sphere,
    Torus,
)
from .textures import load_texture

SHAPE_KIND_OF_CLASS = {
    Sphere: SHAPE_SPHERE,
    Box: SHAPE_BOX,
    Cylinder: SHAPE_CYLINDER,
    Cone: SHAPE_CONE,
    Torus: SHAPE_TORUS,
    Mesh: SHAPE_MESH,
    Csg: SHAPE_CSG,
}

# Listing an area light's shapes costs about as much per shading point as tracing a few
# shadow rays: on the final scene (300 x 300) culling was slower at 1 to 6 rays per light
# (0.68 s against 0.53 s at 1), even at 8 and faster from 12 (0.99 s against 1.11 s), 1.4x at 40
SHADOW_CULLING_MIN_SAMPLES = 8

# Top-level leaves: shapes per leaf, and the node-visit cost relative to one shape test
_TOP_MAX_LEAF = 2
_TOP_TRAVERSAL_COST = 1.0


class CompiledScene(NamedTuple):
    packed: PackedScene
    warnings: list[str]
    triangles: int  # triangles packed, each mesh counted once
    mesh_bytes: int  # bytes of all mesh arrays (BVH nodes, corners, normals, UVs)


def pack_scene(scene: Scene, settings: RenderSettings) -> PackedScene:
    """Validate `scene` and `settings`, then pack them. Raises `SceneError` on bad input."""
    return compile_scene(scene, settings).packed


def compile_scene(scene: Scene, settings: RenderSettings) -> CompiledScene:
    """Validate and pack, returning the warnings (such as degenerate triangles dropped)."""
    scene.validate()
    settings.validate()

    # Rows of the shape table: the scene's shapes, then the operands of its CSG trees
    csg_tables, csg_of_row = CsgTables(), {}
    for i, shape in enumerate(scene.shapes):
        if isinstance(shape, Csg):
            csg_of_row[i] = add_csg(csg_tables, shape, len(scene.shapes))
    shapes = list(scene.shapes) + [operand for operand, _ in csg_tables.operands]
    world_from_object = np.array(
        [s.world_from_object for s in scene.shapes] + [w for _, w in csg_tables.operands], float
    ).reshape(len(shapes), 4, 4)
    check_fits(estimate(shapes, settings))  # before the textures and meshes are unpacked

    materials, material_index = [], {}
    for shape in shapes:
        if id(shape.material) not in material_index:
            material_index[id(shape.material)] = len(materials)
            materials.append((shape.material, shape.owner))
    textures, texture_index = [], {}
    for material, user in materials:
        texture = material.texture
        if texture is not None and id(texture) not in texture_index:
            owner = f"material '{material.name}' (on {user})"
            texture_index[id(texture)] = len(textures)
            textures.append(load_texture(texture, owner))

    tables, mesh_index = MeshTables(), {}
    for shape in shapes:
        if isinstance(shape, Mesh) and id(shape.mesh) not in mesh_index:
            mesh_index[id(shape.mesh)] = add_mesh(tables, shape.mesh)

    n = len(shapes)
    param = np.zeros((n, 2))
    shape_index = np.full(n, -1, np.int32)
    box_lo, box_hi = np.full((n, 3), -1.0), np.full((n, 3), 1.0)  # object-space boxes
    for i, shape in enumerate(shapes):
        if isinstance(shape, Csg):
            shape_index[i] = csg_of_row[i]
        elif isinstance(shape, Torus):
            param[i] = shape.major_radius, shape.minor_radius
            reach = shape.major_radius + shape.minor_radius
            box_hi[i] = reach, reach, shape.minor_radius
            box_lo[i] = -box_hi[i]
        elif isinstance(shape, Mesh):
            m = mesh_index[id(shape.mesh)]
            shape_index[i] = m
            box_lo[i], box_hi[i] = tables.lo[m], tables.hi[m]
    object_from_world = np.linalg.inv(world_from_object)[:, :3] if n else np.empty((0, 3, 4))
    lo, hi = _world_boxes(world_from_object, box_lo, box_hi)
    for i, csg in csg_of_row.items():
        lo[i], hi[i] = csg_world_box(csg_tables.program, *csg_tables.ranges[csg], lo, hi)
    # Only the scene's own shapes enter the top level (CSG operands are reached through
    # their tree); meshes left without triangles (all degenerate) and CSG solids whose
    # operands' boxes do not overlap have nothing to hit: leave them out
    solid = np.array(
        [i < len(scene.shapes) and np.all(lo[i] <= hi[i]) and (
            not isinstance(s, Mesh) or len(tables.lo) and _mesh_has_triangles(tables, s, mesh_index)
        ) for i, s in enumerate(shapes)], bool
    ).reshape(-1)  # fmt: skip
    top_lo, top_hi, top_info, top_order = build_bvh(
        lo[solid], hi[solid], _TOP_MAX_LEAF, _TOP_TRAVERSAL_COST
    )
    top_order = np.flatnonzero(solid)[top_order]
    if not solid.any():
        top_info = np.zeros((0, 2), np.int32)

    point_lights = [lt for lt in scene.lights if isinstance(lt, PointLight)]
    area_lights = [lt for lt in scene.lights if isinstance(lt, AreaLight)]
    suns = [lt for lt in scene.lights if isinstance(lt, DirectionalLight)]
    toward = [-np.asarray(lt.direction, float) / np.linalg.norm(lt.direction) for lt in suns]

    def rows(values, width=3):
        return np.array(values, float).reshape(-1, width)

    frame = Frame(
        camera=_pack_camera(scene, settings),
        lens=np.array([scene.camera.aperture_radius, scene.camera.focal_distance], float),
        ambient=np.asarray(scene.ambient, float),
        background=np.asarray(scene.background, float),
        options=_pack_options(settings),
    )
    geometry = Geometry(
        top_bounds=np.ascontiguousarray(np.hstack([top_lo, top_hi])),
        top_info=np.ascontiguousarray(top_info, np.int32),
        top_order=np.ascontiguousarray(top_order, np.int32),
        shape_kind=np.array([SHAPE_KIND_OF_CLASS[type(s)] for s in shapes], np.int32),
        shape_object_from_world=object_from_world,
        shape_param=param,
        shape_index=shape_index,
        shape_transparency=_shadow_transparency(shapes, len(scene.shapes)),
        shape_bounds=np.ascontiguousarray(np.hstack([lo, hi]).reshape(n, 6)),
        mesh_root=np.array(tables.root, np.int32),
        node_boxes=concatenated(tables.node_boxes, (0, 6, WIDTH), np.float32),
        node_links=concatenated(tables.node_links, (0, WIDTH), np.int32),
        tri_corners=concatenated(tables.tri_corners, (0, 9, LEAF_WIDTH), np.float32),
        csg_range=np.array(csg_tables.ranges, np.int32).reshape(-1, 2),
        csg_program=np.array(csg_tables.program, np.int32),
    )
    surfaces = Surfaces(
        shape_material=np.array([material_index[id(s.material)] for s in shapes], np.int32),
        mesh_tri_offset=np.array(tables.tri_offset, np.int64),
        mesh_normal_offset=np.array(tables.normal_offset, np.int64),
        mesh_uv_offset=np.array(tables.uv_offset, np.int64),
        tri_smooth=concatenated(tables.tri_smooth, (0,), np.uint8),
        tri_normal_index=concatenated(tables.tri_normal_index, (0, 3), np.int32),
        normals=concatenated(tables.normals, (0, 3), np.float32),
        tri_uv_index=concatenated(tables.tri_uv_index, (0, 3), np.int32),
        uvs=concatenated(tables.uvs, (0, 2), np.float32),
    )
    materials = Materials(
        diffuse=rows([m.diffuse for m, _ in materials]),
        specular=rows([m.specular for m, _ in materials]),
        shininess=np.array([m.shininess for m, _ in materials], float),
        reflectivity=np.array([m.reflectivity for m, _ in materials], float),
        transparency=np.array([m.transparency for m, _ in materials], float),
        ior=rows([(m.outer_ior, m.inner_ior) for m, _ in materials], 2),
        texture=np.array([texture_index.get(id(m.texture), -1) for m, _ in materials], np.int32),
        texture_pixels=concatenated([t.reshape(-1, 3) for t in textures], (0, 3), np.float32),
        texture_offset=np.cumsum([0] + [t.shape[0] * t.shape[1] for t in textures])[:-1].astype(
            np.int64
        ),
        texture_size=np.array([(t.shape[1], t.shape[0]) for t in textures], np.int64).reshape(
            -1, 2
        ),
    )
    lights = Lights(
        point_position=rows([lt.position for lt in point_lights]),
        point_intensity=rows([lt.intensity for lt in point_lights]),
        point_attenuation=rows([lt.attenuation for lt in point_lights]),
        area_centre=rows([lt.centre for lt in area_lights]),
        area_edge_u=rows([lt.edge_u for lt in area_lights]),
        area_edge_v=rows([lt.edge_v for lt in area_lights]),
        area_intensity=rows([lt.intensity for lt in area_lights]),
        area_attenuation=rows([lt.attenuation for lt in area_lights]),
        sun_toward=rows(toward),
        sun_intensity=rows([lt.intensity for lt in suns]),
    )
    packed = kernel_ready(PackedScene(frame, geometry, surfaces, materials, lights))
    warnings = [
        f"mesh '{name}': dropped {count} degenerate (zero-area) triangle"
        + ("s" if count != 1 else "")
        for name, count in tables.dropped.items()
    ]
    mesh_fields = [
        "node_boxes",
        "node_links",
        "tri_corners",
        "tri_smooth",
        "tri_normal_index",
        "normals",
        "tri_uv_index",
        "uvs",
    ]
    mesh_bytes = sum(
        getattr(group, name).nbytes
        for group in (geometry, surfaces)
        for name in mesh_fields
        if name in group._fields
    )
    return CompiledScene(packed, warnings, tables.counts["tris"], mesh_bytes)


def kernel_ready(packed: PackedScene) -> PackedScene:
    """Every array of the packed scene C-contiguous, aligned and writable, made so here and
    nowhere else. numba compiles an entry kernel anew for each array layout or read-only flag
    it is handed, and each compile costs the user a minute or more: a slice of the inverse
    transforms, say, is C-contiguous for one shape and strided for several. (dtypes and ranks
    are fixed where each array is built; `tests/core/test_kernel_signature.py` checks all.)"""
    return PackedScene(
        *(
            type(group)(*(np.require(a, requirements=["C", "A", "W"]) for a in group))
            for group in packed
        )
    )


def _shadow_transparency(shapes: list, scene_shapes: int) -> np.ndarray:
    """What each row lets through per surface crossed by a shadow ray: its material's
    transparency; 1 for a scene shape that casts no shadow (kernels skip such rows, which
    is exact: 1^crossings = 1); for a CSG row 0, as its operands' rows decide."""
    tau = np.empty(len(shapes))
    for i, shape in enumerate(shapes):
        if i < scene_shapes and not shape.casts_shadows:
            tau[i] = 1.0
        else:
            tau[i] = 0.0 if isinstance(shape, Csg) else shape.material.transparency
    return tau


def _mesh_has_triangles(tables: MeshTables, shape: Mesh, mesh_index: dict) -> bool:
    m = mesh_index[id(shape.mesh)]
    end = tables.tri_offset[m + 1] if m + 1 < len(tables.tri_offset) else tables.counts["slots"]
    return end > tables.tri_offset[m]


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


def _pack_options(settings: RenderSettings) -> np.ndarray:
    options = np.zeros(OPTION_COUNT, np.int64)
    options[OPTION_MAX_DEPTH] = settings.max_depth
    options[OPTION_PIXEL_SAMPLES] = settings.pixel_samples
    options[OPTION_PIXEL_PATTERN] = PIXEL_PATTERNS[settings.pixel_sampling]
    options[OPTION_SHADOW_SAMPLES] = settings.shadow_samples
    options[OPTION_SHADOW_PATTERN] = SHADOW_PATTERNS[settings.shadow_sampling]
    options[OPTION_SEED] = settings.seed
    options[OPTION_SHADOW_CULLING] = (
        settings.shadow_culling and settings.shadow_samples >= SHADOW_CULLING_MIN_SAMPLES
    )
    return options


def _pack_camera(scene: Scene, settings: RenderSettings) -> np.ndarray:
    cam = scene.camera
    forward = np.asarray(cam.view, float)
    forward /= np.linalg.norm(forward)
    right = np.cross(forward, np.asarray(cam.up, float))
    right /= np.linalg.norm(right)
    up = np.cross(right, forward)
    half_height = math.tan(math.radians(cam.fovy) / 2.0)
    half_width = half_height * settings.width / settings.height
    # The ray through the image centre: shifted in the image plane, still one unit along
    # the view direction, so the plane in focus stays perpendicular to the view
    centre = forward + right * half_width * cam.shift[0] + up * half_height * cam.shift[1]
    return np.array([cam.eye, centre, right * half_width, up * half_height], float)
