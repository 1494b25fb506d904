"""Making Blender data the way a user would: stand-in meshes tagged as exact shapes, meshes
from triangles, materials with the Whitted panel's values, Boolean cuts, placement.

The one builder shared by the Add menu (`ui.add_menu`), the Lua importer (`lua.build`) and
the sample scenes (`sample_blends/scene_kit.py`), so that what each makes exports the same.
Everything goes through `bpy.data` and `foreach_set`, not operators: it works in `blender -b`,
from a timer or a modal operator, whatever the context.
"""

from __future__ import annotations

import math

import bmesh
import bpy
import numpy as np
from mathutils import Matrix

from .compat import give_nodes

# Segments around and along each stand-in unless the caller asks for others: Blender's Add
# menu's own, a torus's 48 x 16 rather than 48 x 12 so its tube looks round
DETAIL = {"SPHERE": (32, 16), "CYLINDER": (32, 1), "CONE": (32, 1), "TORUS": (48, 16)}
CURVED = {"SPHERE", "CYLINDER", "CONE", "TORUS"}


def stand_in(tag: str, name: str, radii=(1.0, 0.25), around=None, along=None):
    """The viewport mesh of a shape tagged `tag` (SPHERE, CUBE, CYLINDER, CONE, TORUS) in its
    object space as Whitted renders it: the unit sphere, the cube [-1, 1]^3, the cylinder and
    cone of radius 1 from z = -1 to 1 (the cone's apex at the top), a torus of the radii
    given. Curved shapes are smooth shaded."""
    default_around, default_along = DETAIL.get(tag, (0, 0))
    around, along = around or default_around, along or default_along
    if tag == "TORUS":
        vertices, quads, corner_uvs = _torus(*radii, rings=around, sides=along)
        mesh = polygon_mesh(name, vertices, quads)
        mesh.uv_layers.new(name="UVMap").data.foreach_set("uv", corner_uvs.ravel())
    else:
        mesh = bpy.data.meshes.new(name)
        bm = bmesh.new()
        bm.loops.layers.uv.new("UVMap")  # UVs as Blender's primitives have, for the viewport
        if tag == "SPHERE":
            bmesh.ops.create_uvsphere(bm, u_segments=around, v_segments=along, radius=1.0,
                                      calc_uvs=True)  # fmt: skip
        elif tag == "CUBE":
            bmesh.ops.create_cube(bm, size=2.0, calc_uvs=True)
        else:
            top = 1.0 if tag == "CYLINDER" else 0.0
            bmesh.ops.create_cone(bm, cap_ends=True, segments=around, radius1=1.0,
                                  radius2=top, depth=2.0, calc_uvs=True)  # fmt: skip
        bm.to_mesh(mesh)
        bm.free()
    smooth(mesh, tag in CURVED)
    return mesh


def shape_object(tag: str, name: str, radii=(1.0, 0.25), mesh=None):
    """A new object tagged as the exact shape `tag`, its stand-in mesh made (or `mesh`
    shared); a torus carries its radii."""
    obj = bpy.data.objects.new(name, mesh or stand_in(tag, name, radii))
    obj.whitted.shape = tag
    if tag == "TORUS":
        obj.whitted.major_radius, obj.whitted.minor_radius = radii
    return obj


def _torus(major: float, minor: float, rings: int, sides: int):
    """(vertices, quads, their corners' UVs) of a torus about z, as Blender's Add > Torus
    makes it: u around the ring, v around the tube, each from 0 to 1 across the seam."""
    u, v = np.meshgrid(np.linspace(0, 2 * np.pi, rings, endpoint=False),
                       np.linspace(0, 2 * np.pi, sides, endpoint=False), indexing="ij")  # fmt: skip
    radius = major + minor * np.cos(v)
    points = np.stack([radius * np.cos(u), radius * np.sin(u), minor * np.sin(v)], -1)
    i, j = (a.ravel() for a in np.meshgrid(np.arange(rings), np.arange(sides), indexing="ij"))
    ring, side = (i + 1) % rings, (j + 1) % sides
    quads = np.stack([i * sides + j, ring * sides + j, ring * sides + side, i * sides + side], 1)
    # Unwrapped: the corners past the seam take u = 1 or v = 1, not 0
    u_corner = np.stack([i, i + 1, i + 1, i], 1) / rings
    v_corner = np.stack([j, j, j + 1, j + 1], 1) / sides
    corner_uvs = np.stack([u_corner, v_corner], -1).astype(np.float32)
    return points.reshape(-1, 3), quads, corner_uvs


def polygon_mesh(name: str, vertices: np.ndarray, faces: np.ndarray):
    """A mesh of equal-sized faces (f, k) over vertices (v, 3), through `foreach_set`."""
    faces = np.asarray(faces, np.int32)
    mesh = bpy.data.meshes.new(name)
    mesh.vertices.add(len(vertices))
    mesh.vertices.foreach_set("co", np.asarray(vertices, np.float32).ravel())
    mesh.loops.add(faces.size)
    mesh.loops.foreach_set("vertex_index", faces.ravel())
    mesh.polygons.add(len(faces))
    corners = faces.shape[1]
    mesh.polygons.foreach_set("loop_start", np.arange(0, faces.size, corners, dtype=np.int32))
    if bpy.app.version < (4, 0, 0):  # read-only from 4.0, where loop_start decides it
        mesh.polygons.foreach_set("loop_total", np.full(len(faces), corners, np.int32))
    mesh.update(calc_edges=True)
    return mesh


def smooth(mesh, flag: bool) -> None:
    mesh.polygons.foreach_set("use_smooth", np.full(len(mesh.polygons), flag))


def triangle_mesh_data(name: str, vertices, triangles, corner_uvs=None, smooth_faces=True):
    """A mesh of triangles (t, 3) over vertices (v, 3), with corner UVs (t, 3, 2) if given,
    every face smooth or every face flat."""
    mesh = polygon_mesh(name, vertices, triangles)
    if corner_uvs is not None:
        layer = mesh.uv_layers.new(name="UVMap")
        layer.data.foreach_set("uv", np.asarray(corner_uvs, np.float32).ravel())
    smooth(mesh, smooth_faces)
    return mesh


def mesh_from_triangles(triangle_mesh, name: str):
    """A Blender mesh holding a core `TriangleMesh`: its triangles, smooth with its normals
    as custom normals, and its texture coordinates."""
    triangles = np.asarray(triangle_mesh.triangles, np.int32)
    mesh = triangle_mesh_data(name, triangle_mesh.vertices, triangles, triangle_mesh.corner_uvs)
    normals = triangle_mesh.corner_normals
    if normals is None and triangle_mesh.vertex_normals is not None:
        normals = np.asarray(triangle_mesh.vertex_normals)[triangles]
    if normals is not None:
        if bpy.app.version < (4, 1, 0):
            mesh.use_auto_smooth = True  # custom normals count only with auto smooth before 4.1
            mesh.auto_smooth_angle = math.pi
        mesh.normals_split_custom_set(np.asarray(normals, np.float32).reshape(-1, 3))
    return mesh


def whitted_material(name, diffuse=(0.7, 0.7, 0.7), specular=(0.3, 0.3, 0.3), shininess=25.0,
                     reflectivity=0.0, transparency=0.0, outer_ior=1.0, inner_ior=1.5,
                     image=None):  # fmt: skip
    """A material with the Whitted panel switched on (the report's gr.material values); the
    Principled BSDF gets the same base colour and the texture `image`, for the viewport."""
    material = bpy.data.materials.new(name)
    give_nodes(material)
    tree = material.node_tree
    principled = next(n for n in tree.nodes if n.type == "BSDF_PRINCIPLED")
    principled.inputs["Base Color"].default_value = (*diffuse, 1.0)
    material.diffuse_color = (*diffuse, 1.0)
    if image is not None:
        node = tree.nodes.new("ShaderNodeTexImage")
        node.image = image
        node.location = (-300, 300)
        tree.links.new(node.outputs["Color"], principled.inputs["Base Color"])
    settings = material.whitted
    settings.use_whitted = True
    settings.specular = specular
    settings.shininess = shininess
    settings.reflectivity = reflectivity
    settings.transparency = transparency
    settings.outer_ior = outer_ior
    settings.inner_ior = inner_ior
    settings.image = image
    return material


def add_boolean(target, operation: str, operand):
    """A Boolean modifier on `target` (UNION, INTERSECT or DIFFERENCE) with `operand` hidden
    from rendering, as a Blender user does with a cutter: Whitted renders the exact CSG."""
    modifier = target.modifiers.new(f"{operation.title()} {operand.name}", "BOOLEAN")
    modifier.operation = operation
    modifier.object = operand
    operand.hide_render = True
    operand.display_type = "WIRE"
    return modifier


def place(obj, local: np.ndarray) -> None:
    """Put `local` into the object's transform: as location, rotation and scale where it is
    one, else (a shear, from scaling after rotating) whole into the parent inverse matrix,
    which Blender applies as it is."""
    obj.matrix_parent_inverse = Matrix.Identity(4)
    obj.matrix_basis = Matrix(local.tolist())
    size = max(1.0, float(np.abs(local).max()))
    if not np.allclose(np.array(obj.matrix_basis), local, rtol=1e-6, atol=1e-6 * size):
        obj.matrix_basis = Matrix.Identity(4)
        obj.matrix_parent_inverse = Matrix(local.tolist())
