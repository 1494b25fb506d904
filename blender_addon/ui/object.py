"""Object Properties › Whitted Shape: the exact shape a mesh stands in for, and its CSG."""

import bpy

from ..export.csg import OPERATIONS, boolean_modifiers, operand_objects
from .base import WhittedPanel


class WHITTED_PT_object_shape(WhittedPanel, bpy.types.Panel):
    bl_label = "Whitted Shape"
    bl_context = "object"

    @classmethod
    def poll(cls, context):
        return (
            super().poll(context) and context.object is not None and context.object.type == "MESH"
        )

    def draw(self, context):
        layout = self.layout
        layout.use_property_split = True
        obj = context.object
        layout.prop(obj.whitted, "shape")
        if obj.whitted.shape == "TORUS":
            radii = layout.column(align=True)
            radii.prop(obj.whitted, "major_radius", text="Major")
            radii.prop(obj.whitted, "minor_radius", text="Minor")
        booleans = boolean_modifiers(obj)
        if booleans:
            box = layout.box()
            box.label(text="Renders as CSG, exactly:", icon="MOD_BOOLEAN")
            for modifier in booleans:
                operands = ", ".join(o.name for o in operand_objects(modifier)) or "(none)"
                box.label(text=f"{OPERATIONS[modifier.operation]} {operands}")


class WHITTED_PT_object_ray_visibility(WhittedPanel, bpy.types.Panel):
    """Object Properties › Visibility › Ray Visibility: the rays that see the object, as
    Cycles' panel draws them (Blender's own Visibility panel has none for other engines)."""

    bl_label = "Ray Visibility"
    bl_context = "object"
    bl_parent_id = "OBJECT_PT_visibility"

    @classmethod
    def poll(cls, context):
        obj = context.object
        return super().poll(context) and obj is not None and obj.type not in {"LIGHT", "CAMERA"}

    def draw(self, context):
        layout = self.layout
        layout.use_property_split = True
        layout.use_property_decorate = False
        obj = context.object
        column = layout.column(heading="Ray Visibility", align=True)
        column.prop(obj, "visible_camera", text="Camera", toggle=False)
        column.prop(obj, "visible_shadow", text="Shadow", toggle=False)
        column.prop(obj, "visible_glossy", text="Glossy", toggle=False)
        # Cycles' "Transmission" is cut at the default width
        column.prop(obj, "visible_transmission", text="Transmit", toggle=False)
