"""Compile a `Scene` into `PackedScene`: the flat arrays that are all the kernels ever see.

    from .compile import compile_scene
    compiled = compile_scene(scene, settings)   # validates; raises SceneError
    compiled.packed                             # PackedScene: frame, geometry, surfaces, ...

One module a table, called in this order, each for a reason:
1. validate the scene and the settings: nothing is packed from bad input;
2. `frame`: camera, lens, ambient, background, options (needs only the settings);
3. `csg`: each CSG tree's operands become rows after the scene's shapes, so the rows of the
   shape table are known from here on;
4. the memory estimate over those rows (`core.memory_estimate`): a render that cannot fit
   is refused before the textures and meshes below are unpacked;
5. `materials`: the rows' materials and textures (the shape table refers to them by index);
6. `meshes`: each `TriangleMesh` once, with its BVH (the shape table needs their bounds);
7. `shapes`: the shape table and the top-level BVH (`Geometry`);
8. `surfaces`: per row, its material; per triangle, its normals and UVs;
9. `lights`;
10. `caustics`: photons traced through all of the above (core.compile.caustics), into the
   lights' photon arrays.
Every array has a fixed dtype and rank whatever the scene, so the kernels compile once and
load from the cache for every scene after. Scenes without some feature get empty arrays, and
the kernels do no work for it.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from ..kernels.layout import PackedScene
from ..kernels.options import OPTION_GLASS_SHADOWS
from ..memory_estimate import check_fits, estimate
from ..model import Mesh, RenderSettings, Scene
from ..model.shader import EDGE_ATTRIBUTE, TANGENT_ATTRIBUTE, attribute_names
from .caustics import CausticReport, add_caustics
from .csg import owner_rows, pack_csg
from .frame import pack_frame
from .glowing import glowing_shapes
from .lights import pack_lights
from .materials import pack_materials, shadow_powers, shadow_shares
from .meshes import pack_meshes
from .shapes import pack_geometry
from .surfaces import pack_surfaces

# The mesh arrays, in whichever group each lives (for CompiledScene.mesh_bytes)
MESH_FIELDS = ("node_boxes", "node_links", "tri_corners", "tri_smooth", "tri_normal_index",
               "normals", "tri_uv_index", "uvs", "tri_color_index", "colors")  # fmt: skip


class CompiledScene(NamedTuple):
    packed: PackedScene
    warnings: list[str]
    triangles: int  # triangles packed, each mesh counted once
    mesh_bytes: int  # bytes of all mesh arrays (BVH nodes, corners, normals, UVs)
    caustics: CausticReport | None = None  # the photon pass, if any was traced


def pack_scene(scene: Scene, settings: RenderSettings) -> PackedScene:
    """Validate `scene` and `settings`, then pack them. Raises `SceneError` on bad input."""
    return compile_scene(scene, settings).packed


def compile_scene(scene: Scene, settings: RenderSettings, on_photons=None,
                  should_cancel=None) -> CompiledScene:  # fmt: skip
    """Validate and pack, returning the warnings (such as degenerate triangles dropped).
    on_photons and should_cancel: the caustic photon pass's (caustics.add_caustics)."""
    scene.validate()
    settings.validate()
    frame = pack_frame(scene, settings)
    csg, tree_of_row = pack_csg(scene.shapes)
    shapes = list(scene.shapes) + [operand for operand, _ in csg.operands]
    world_from_object = np.array(
        [s.world_from_object for s in scene.shapes] + [w for _, w in csg.operands], float
    ).reshape(len(shapes), 4, 4)
    check_fits(estimate(shapes, settings))
    # the colour attributes the programs read, numbered for the kernels (core.kernels.attributes)
    names = attribute_names([s.material.surface for s in shapes if s.material.surface is not None])
    materials, material_of = pack_materials(shapes, names)
    meshes, mesh_of = pack_meshes(shapes, names)
    graph_of_row = {material_of[id(s.material)]: s.material.surface for s in shapes}
    graphs = [graph_of_row.get(k) for k in range(len(materials.transparency))]
    refraction_passes = settings.glass_shadows == "attenuated"
    lets_through = shadow_shares(materials, graphs, refraction_passes)
    powers = shadow_powers(materials, lets_through, refraction_passes)
    rows = [material_of[id(s.material)] for s in shapes]
    geometry = pack_geometry(scene.shapes, shapes, world_from_object, csg, tree_of_row,
                             meshes, mesh_of, lets_through[rows], powers[rows])  # fmt: skip
    owners = [scene.shapes[row] for row in owner_rows(csg, tree_of_row, len(scene.shapes))]
    surfaces = pack_surfaces(shapes, owners, material_of, meshes)
    # the emissive surfaces' lights last: a varying one's emission is the material's program
    # run on its triangles (core.kernels.glow_bake), which needs the rest packed
    unlit = kernel_ready(PackedScene(frame, geometry, surfaces, materials,
                                     pack_lights(scene.lights, scene.environment)))  # fmt: skip
    glowing = glowing_shapes(scene.shapes, unlit, material_of)
    lights = pack_lights(scene.lights, scene.environment, glowing)
    packed = kernel_ready(unlit._replace(lights=lights))
    packed, caustic_warnings, caustics = add_caustics(packed, settings, on_photons,
                                                      should_cancel, graphs)  # fmt: skip
    packed = kernel_ready(packed)
    warnings = (
        [
            f"mesh '{name}': dropped {count} degenerate (zero-area) triangle"
            + ("s" if count != 1 else "")
            for name, count in meshes.dropped.items()
        ]
        + glowing.warnings
        + caustic_warnings
        + _missing_attributes(shapes)
        + _unabsorbed_shadows(materials, lets_through, shapes, material_of)
    )
    mesh_bytes = sum(
        getattr(group, name).nbytes
        for group in (geometry, surfaces)
        for name in MESH_FIELDS
        if name in group._fields
    )
    return CompiledScene(packed, warnings, meshes.counts["tris"], mesh_bytes, caustics)


def _missing_attributes(shapes: list) -> list[str]:
    """A warning for each mesh whose material reads a colour attribute it lacks (read as 0,
    as Cycles reads a missing attribute; an Attribute node naming a UV map or a number
    attribute reads the same: only colour attributes are exported)."""
    warnings = []
    for shape in shapes:
        surface = shape.material.surface
        if surface is None:
            continue
        if not isinstance(shape, Mesh):
            if EDGE_ATTRIBUTE in attribute_names([surface]):
                text = (f"{shape.owner} is an exact shape: material '{shape.material.name}''s "
                        "Wireframe has no triangle edges to draw on it (used: Fac 0)")  # fmt: skip
                if text not in warnings:
                    warnings.append(text)
            continue
        colors = shape.mesh.corner_colors or {}
        for name in attribute_names([surface]):
            if name in (TANGENT_ATTRIBUTE, EDGE_ATTRIBUTE):  # no tangents: UV gradients
                continue
            if (name or shape.mesh.default_color) not in colors:
                shown = f"colour attribute '{name}'" if name else "default colour attribute"
                text = (f"mesh '{shape.mesh.name}' (on {shape.owner}) has no {shown} that "
                        f"material '{shape.material.name}' reads (read as 0)")  # fmt: skip
                if text not in warnings:
                    warnings.append(text)
    return warnings


def _unabsorbed_shadows(materials, lets_through, shapes, material_of) -> list[str]:
    """A warning for each material that absorbs inside (core.kernels.absorption) and lets
    shadow rays through: they are not absorbed (under Cycles' "blocked" rule no shadow ray
    crosses glass, and its light comes as photons, which are)."""
    warnings = []
    for shape in shapes:
        k = material_of[id(shape.material)]
        if lets_through[k] != 0.0 and materials.absorption[k].max() > 0.0:
            text = (f"material '{shape.material.name}': shadow rays through it are not "
                    "absorbed by its medium (Volume Absorption): its shadow is lighter than "
                    "Cycles'; Glass Shadows 'blocked' with caustics carries the absorbed "
                    "light")  # fmt: skip
            if text not in warnings:
                warnings.append(text)
    return warnings


def with_frame(compiled: CompiledScene, scene: Scene, settings: RenderSettings) -> CompiledScene:
    """`compiled` seen through `scene`'s camera at `settings`' size and sampling: only the
    frame (step 2) is packed again, the geometry, materials and lights are shared. What the
    viewport does when the view moves, and for each of its coarse-to-fine passes. `scene`
    must hold what `compiled` was compiled from, but for its camera, and `settings` its
    glass-shadow rule."""
    scene.camera.validate()
    settings.validate()
    frame = pack_frame(scene, settings)
    if frame.options[OPTION_GLASS_SHADOWS] != compiled.packed.frame.options[OPTION_GLASS_SHADOWS]:
        # the shapes' shadow shares were packed under the compiled rule
        raise ValueError("with_frame: settings.glass_shadows differs from the compiled scene's")
    frame = kernel_ready(PackedScene(frame, *compiled.packed[1:]))[0]
    return compiled._replace(packed=compiled.packed._replace(frame=frame))


def kernel_ready(packed: PackedScene) -> PackedScene:
    """Every array of the packed scene C-contiguous, aligned and writable, made so here and
    nowhere else. numba compiles an entry kernel anew for each array layout or read-only flag
    it is handed, and each compile costs the user a minute or more: a slice of the inverse
    transforms, say, is C-contiguous for one shape and strided for several. (dtypes and ranks
    are fixed where each array is built; tests/core/kernels/test_kernel_signature.py checks
    all.)"""
    return PackedScene(
        *(
            type(group)(*(np.require(a, requirements=["C", "A", "W"]) for a in group))
            for group in packed
        )
    )
