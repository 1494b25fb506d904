"""Add › Whitted: a stand-in mesh, already tagged as the exact shape it stands in for
(made by `blender_data`, as the Lua importer and the sample scenes make theirs)."""

import bpy

from ..blender_data import shape_object
from ..properties.shape_tags import EXACT


class WHITTED_OT_add_shape(bpy.types.Operator):
    """Add a mesh stand-in tagged to render as an exact shape"""

    bl_idname = "whitted.add_shape"
    bl_label = "Add Whitted Shape"
    bl_options = {"REGISTER", "UNDO"}

    shape: bpy.props.EnumProperty(
        name="Shape", items=[(tag.tag, tag.label, tag.description) for tag in EXACT]
    )

    def execute(self, context):
        # Placed, selected and made active as Blender's own Add menu does
        obj = shape_object(self.shape, f"Whitted {self.shape.title()}")
        context.collection.objects.link(obj)
        obj.location = context.scene.cursor.location
        for other in context.selected_objects:
            other.select_set(False)
        obj.select_set(True)
        context.view_layer.objects.active = obj
        return {"FINISHED"}


class WHITTED_MT_add(bpy.types.Menu):
    bl_idname = "WHITTED_MT_add"
    bl_label = "Whitted"

    def draw(self, context):
        for tag in EXACT:
            entry = self.layout.operator(WHITTED_OT_add_shape.bl_idname, text=tag.label,
                                         icon=tag.icon)  # fmt: skip
            entry.shape = tag.tag


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
