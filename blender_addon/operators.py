"""Add › Whitted: a Blender primitive, already tagged as the exact shape it stands in for."""

import bpy

PRIMITIVES = (
    ("SPHERE", "Sphere", "MESH_UVSPHERE", "primitive_uv_sphere_add"),
    ("CUBE", "Cube", "MESH_CUBE", "primitive_cube_add"),
    ("CYLINDER", "Cylinder", "MESH_CYLINDER", "primitive_cylinder_add"),
    ("CONE", "Cone", "MESH_CONE", "primitive_cone_add"),
    ("TORUS", "Torus", "MESH_TORUS", "primitive_torus_add"),
)


class WHITTED_OT_add_shape(bpy.types.Operator):
    """Add a mesh stand-in tagged to render as an exact shape"""

    bl_idname = "whitted.add_shape"
    bl_label = "Add Whitted Shape"
    bl_options = {"REGISTER", "UNDO"}

    shape: bpy.props.EnumProperty(
        name="Shape", items=[(key, label, "") for key, label, _, _ in PRIMITIVES]
    )

    def execute(self, context):
        operator = next(op for key, _, _, op in PRIMITIVES if key == self.shape)
        getattr(bpy.ops.mesh, operator)()
        obj = context.active_object
        obj.whitted.shape = self.shape
        obj.name = f"Whitted {self.shape.title()}"
        return {"FINISHED"}


class WHITTED_MT_add(bpy.types.Menu):
    bl_idname = "WHITTED_MT_add"
    bl_label = "Whitted"

    def draw(self, context):
        for key, label, icon, _ in PRIMITIVES:
            self.layout.operator(WHITTED_OT_add_shape.bl_idname, text=label, icon=icon).shape = key


def _add_menu_entry(self, context):
    self.layout.menu(WHITTED_MT_add.bl_idname, icon="SHADING_RENDERED")


def register():
    bpy.utils.register_class(WHITTED_OT_add_shape)
    bpy.utils.register_class(WHITTED_MT_add)
    bpy.types.VIEW3D_MT_add.append(_add_menu_entry)


def unregister():
    bpy.types.VIEW3D_MT_add.remove(_add_menu_entry)
    bpy.utils.unregister_class(WHITTED_MT_add)
    bpy.utils.unregister_class(WHITTED_OT_add_shape)
