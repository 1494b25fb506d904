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
            layout.prop(obj.whitted, "major_radius")
            layout.prop(obj.whitted, "minor_radius")
        booleans = boolean_modifiers(obj)
        if booleans:
            box = layout.box()
            box.label(text="Renders as CSG, exactly:", icon="MOD_BOOLEAN")
            for modifier in booleans:
                operands = ", ".join(o.name for o in operand_objects(modifier)) or "(none)"
                box.label(text=f"{OPERATIONS[modifier.operation]} {operands}")
