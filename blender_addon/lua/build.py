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

import bpy
import numpy as np

from ..blender_data import (
    add_boolean,
    mesh_from_triangles,
    place,
    shape_object,
    stand_in,
    whitted_material,
)
from ..core.cs488.graph import Z_TO_MINUS_Y, CsgNode, GeometryNode
from ..core.cs488.render_call import UNSET_MATERIAL

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
        # The Whitted Shape items are the script's kinds in capitals: SPHERE, ..., MESH
        obj = shape_object(node.kind.upper(), node.name, node.radii, mesh=self.mesh_data(node))
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
        add_boolean(left, OPERATIONS[node.operation], right)
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
                self.shared[key] = stand_in(node.kind.upper(), f"Whitted {node.kind}", node.radii)
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


def blender_material(core_material):
    """A Whitted material of a script's gr.material, its texture loaded as the report read
    it (the file's values as they are, no sRGB decoding, unless the script asks)."""
    texture = core_material.texture
    image = None
    if texture is not None:
        image = bpy.data.images.load(str(texture.path), check_existing=True)
        image.colorspace_settings.name = "Non-Color" if not texture.srgb else "sRGB"
    return whitted_material(
        core_material.name,
        diffuse=core_material.diffuse,
        specular=core_material.specular,
        shininess=core_material.shininess,
        reflectivity=core_material.reflectivity,
        transparency=core_material.transparency,
        outer_ior=core_material.outer_ior,
        inner_ior=core_material.inner_ior,
        image=image,
    )
