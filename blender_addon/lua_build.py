"""A CS488 gr.render call (`core.cs488.RenderCall`) built as Blender data.

Everything is made the way a Blender user would make it, so the export reads it back as the
same core scene: nodes become Empties and objects parented as in the script (a node under
two parents is built once per path), shapes are mesh stand-ins tagged with their exact shape,
`gr.csg` becomes Boolean modifiers whose operands are hidden and parented to the object they
cut, materials carry the Whitted panel's values, lights and the camera are Blender's own. The
script's y-up world hangs under one root Empty turned +90 degrees about x, so it stands
upright in Blender's z-up world.
"""

from __future__ import annotations

import math

import bmesh
import bpy
import numpy as np
from mathutils import Matrix

from .compat import give_nodes
from .core.cs488.graph import Z_TO_MINUS_Y, CsgNode, GeometryNode
from .core.cs488.render_call import UNSET_MATERIAL

# The script's y up onto Blender's z up (and its z, towards the viewer, onto -y)
Y_UP_TO_Z_UP = Z_TO_MINUS_Y
OPERATIONS = {"union": "UNION", "intersection": "INTERSECT", "diff": "DIFFERENCE"}  # gr.csg words


class Builder:
    """Builds the objects of one render call into `collection`, sharing meshes, stand-ins and
    materials between objects (and between calls, through `shared`)."""

    def __init__(self, collection, shared: dict):
        self.collection = collection
        self.shared = shared

    def link(self, obj, parent, local: np.ndarray):
        self.collection.objects.link(obj)
        obj.parent = parent
        place(obj, local)
        return obj

    # The node graph
    def node(self, node, parent, local: np.ndarray) -> None:
        """`node` with its shape and children, placed by `local` under `parent`."""
        here = local @ node.matrix
        owner = parent
        if isinstance(node, CsgNode):
            self.solid(node, parent, here, None)
        elif isinstance(node, GeometryNode) and not node.children:
            self.shape(node, parent, here @ node.shape_matrix, None)
        else:
            owner = self.link(bpy.data.objects.new(node.name, None), parent, here)
            owner.empty_display_size = 0.5
            if isinstance(node, GeometryNode):
                self.shape(node, owner, node.shape_matrix, None)
        # Children hang under the node's Empty, or, where it has none, beside its object
        for child in node.children:
            self.node(child, owner, np.eye(4) if owner is not parent else here)

    def shape(self, node: GeometryNode, parent, local: np.ndarray, inherited):
        spec = node.material
        material = spec.core if spec is not None else inherited or UNSET_MATERIAL
        obj = bpy.data.objects.new(node.name, self.mesh_data(node))
        obj.whitted.shape = node.kind.upper()  # the Whitted Shape items: SPHERE, ..., MESH
        if node.kind == "torus":
            obj.whitted.major_radius, obj.whitted.minor_radius = node.radii
        self.link(obj, parent, local)
        # The mesh is shared; its one material slot is linked to each object's own material
        slot = obj.material_slots[0]
        slot.link = "OBJECT"
        slot.material = self.material(material)
        return obj

    def solid(self, node, parent, local: np.ndarray, inherited):
        """A shape or CSG node as one object: a CSG node is its first operand's object with
        a Boolean modifier cutting (or joining) the second, parented to it and hidden."""
        own = node.material.core if node.material is not None else inherited
        if not isinstance(node, CsgNode):
            return self.shape(node, parent, local @ node.shape_matrix, own)
        left = self.solid(node.left, parent, local @ node.left.matrix, own)
        # The second operand is placed in the frame of the first's object (its parent)
        to_left = np.linalg.inv(relative(left, parent)) @ local
        right = self.solid(node.right, left, to_left @ node.right.matrix, own)
        modifier = left.modifiers.new(f"{node.operation.title()} {right.name}", "BOOLEAN")
        modifier.operation = OPERATIONS[node.operation]
        modifier.object = right
        right.hide_render = True
        right.display_type = "WIRE"
        return left

    # Data shared between objects
    def mesh_data(self, node: GeometryNode):
        if node.kind == "mesh":
            key = ("mesh", id(node.mesh))
            if key not in self.shared:
                self.shared[key] = mesh_from_triangles(node.mesh, node.name)
        else:
            key = (node.kind, node.radii)
            if key not in self.shared:
                self.shared[key] = stand_in(node.kind, node.radii)
        mesh = self.shared[key]
        if not mesh.materials:
            mesh.materials.append(None)
        return mesh

    def material(self, core_material):
        key = ("material", id(core_material))
        if key not in self.shared:
            self.shared[key] = blender_material(core_material)
        return self.shared[key]


def relative(obj, ancestor) -> np.ndarray:
    """`obj`'s matrix in `ancestor`'s frame, from the parent chain as built (before Blender
    evaluates world matrices)."""
    matrix = np.eye(4)
    while obj is not None and obj is not ancestor:
        basis = np.array(obj.matrix_parent_inverse) @ np.array(obj.matrix_basis)
        matrix = basis @ matrix
        obj = obj.parent
    return matrix


def place(obj, local: np.ndarray) -> None:
    """Put `local` into the object's transform: as location, rotation and scale where it is
    one, else (a shear, from scaling after rotating) whole into the parent inverse matrix,
    which Blender applies as it is."""
    obj.matrix_parent_inverse = Matrix.Identity(4)
    obj.matrix_basis = Matrix(local.tolist())
    if not np.allclose(np.array(obj.matrix_basis), local, rtol=1e-6, atol=1e-6 * _size(local)):
        obj.matrix_basis = Matrix.Identity(4)
        obj.matrix_parent_inverse = Matrix(local.tolist())


def _size(matrix: np.ndarray) -> float:
    return max(1.0, float(np.abs(matrix).max()))


def stand_in(kind: str, radii):
    """The viewport mesh of a tagged shape: Blender's own primitive of that kind."""
    if kind == "torus":
        mesh = _polygon_mesh(f"Whitted {kind}", *_torus(*radii))
    else:
        mesh = bpy.data.meshes.new(f"Whitted {kind}")
        bm = bmesh.new()
        if kind == "sphere":
            bmesh.ops.create_uvsphere(bm, u_segments=32, v_segments=16, radius=1.0)
        elif kind == "cube":
            bmesh.ops.create_cube(bm, size=2.0)
        else:
            top = 1.0 if kind == "cylinder" else 0.0
            bmesh.ops.create_cone(bm, cap_ends=True, segments=32, radius1=1.0, radius2=top,
                                  depth=2.0)  # fmt: skip
        bm.to_mesh(mesh)
        bm.free()
    _smooth(mesh, kind != "cube")
    return mesh


def _torus(major: float, minor: float, rings: int = 48, sides: int = 16):
    """(vertices, quads) of a torus about z, as Blender's Add > Torus makes it."""
    u, v = np.meshgrid(np.linspace(0, 2 * np.pi, rings, endpoint=False),
                       np.linspace(0, 2 * np.pi, sides, endpoint=False), indexing="ij")  # fmt: skip
    radius = major + minor * np.cos(v)
    points = np.stack([radius * np.cos(u), radius * np.sin(u), minor * np.sin(v)], -1)
    i, j = (a.ravel() for a in np.meshgrid(np.arange(rings), np.arange(sides), indexing="ij"))
    ring, side = (i + 1) % rings, (j + 1) % sides
    quads = np.stack([i * sides + j, ring * sides + j, ring * sides + side, i * sides + side], 1)
    return points.reshape(-1, 3), quads


def _polygon_mesh(name: str, vertices: np.ndarray, faces: np.ndarray):
    """A mesh of equal-sized faces (f, k) over vertices (v, 3), through `foreach_set`."""
    mesh = bpy.data.meshes.new(name)
    mesh.vertices.add(len(vertices))
    mesh.vertices.foreach_set("co", np.asarray(vertices, np.float32).ravel())
    mesh.loops.add(faces.size)
    mesh.loops.foreach_set("vertex_index", np.asarray(faces, np.int32).ravel())
    mesh.polygons.add(len(faces))
    corners = faces.shape[1]
    mesh.polygons.foreach_set("loop_start", np.arange(0, faces.size, corners, dtype=np.int32))
    if bpy.app.version < (4, 0, 0):  # read-only from 4.0, where loop_start decides it
        mesh.polygons.foreach_set("loop_total", np.full(len(faces), corners, np.int32))
    mesh.update(calc_edges=True)
    return mesh


def _smooth(mesh, smooth: bool) -> None:
    flags = np.full(len(mesh.polygons), smooth)
    mesh.polygons.foreach_set("use_smooth", flags)


def mesh_from_triangles(triangle_mesh, name: str):
    """A Blender mesh holding a core `TriangleMesh`: its triangles, smooth with its normals
    as custom normals, and its texture coordinates."""
    triangles = np.asarray(triangle_mesh.triangles, np.int32)
    mesh = _polygon_mesh(name, triangle_mesh.vertices, triangles)
    if triangle_mesh.corner_uvs is not None:
        layer = mesh.uv_layers.new(name="UVMap")
        layer.data.foreach_set("uv", np.asarray(triangle_mesh.corner_uvs, np.float32).ravel())
    _smooth(mesh, True)
    normals = triangle_mesh.corner_normals
    if normals is None and triangle_mesh.vertex_normals is not None:
        normals = np.asarray(triangle_mesh.vertex_normals)[triangles]
    if normals is not None:
        if bpy.app.version < (4, 1, 0):
            mesh.use_auto_smooth = True  # custom normals count only with auto smooth before 4.1
            mesh.auto_smooth_angle = math.pi
        mesh.normals_split_custom_set(np.asarray(normals, np.float32).reshape(-1, 3))
    return mesh


def blender_material(core_material):
    """A material with the Whitted panel's values (the report's gr.material), and the same
    colour and texture on its Principled BSDF for the viewport."""
    material = bpy.data.materials.new(core_material.name)
    give_nodes(material)
    tree = material.node_tree
    principled = next(n for n in tree.nodes if n.type == "BSDF_PRINCIPLED")
    principled.inputs["Base Color"].default_value = (*core_material.diffuse, 1.0)
    material.diffuse_color = (*core_material.diffuse, 1.0)
    settings = material.whitted
    settings.use_whitted = True
    settings.specular = core_material.specular
    settings.shininess = core_material.shininess
    settings.reflectivity = core_material.reflectivity
    settings.transparency = core_material.transparency
    settings.outer_ior = core_material.outer_ior
    settings.inner_ior = core_material.inner_ior
    texture = core_material.texture
    if texture is not None:
        image = bpy.data.images.load(str(texture.path), check_existing=True)
        # The report used the file's values as they are: no sRGB decoding
        image.colorspace_settings.name = "Non-Color" if not texture.srgb else "sRGB"
        settings.image = image
        node = tree.nodes.new("ShaderNodeTexImage")
        node.image = image
        node.location = (-300, 300)
        tree.links.new(node.outputs["Color"], principled.inputs["Base Color"])
    return material
