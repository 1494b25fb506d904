"""Light Properties › Whitted Light: which lights render, and their attenuation."""

import bpy

from .base import WhittedPanel


class WHITTED_PT_light(WhittedPanel, bpy.types.Panel):
    bl_label = "Whitted Light"
    bl_context = "data"
    context_member = "light"

    def draw(self, context):
        layout = self.layout
        layout.use_property_split = True
        if context.light.type == "SUN":
            layout.label(text="Parallel light along the object's -Z axis", icon="INFO")
            return
        if context.light.type not in {"POINT", "AREA"}:
            layout.label(text="Whitted renders point, sun and area lights", icon="ERROR")
            return
        if context.light.type == "AREA" and context.light.shape not in {"SQUARE", "RECTANGLE"}:
            layout.label(text="Area lights must be square or rectangular", icon="ERROR")
        layout.prop(context.light.whitted, "attenuation")
