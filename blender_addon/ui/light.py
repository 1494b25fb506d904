"""Light Properties › Light, Whitted's: the type, colour, power and area shape it reads (in
place of Blender's Light and Area Shape panels, so each shows once), and the report's
attenuation."""

import bpy

from .base import WhittedPanel

ATTENUATION_LABELS = ("Constant", "Linear", "Quadratic")


class WHITTED_PT_light(WhittedPanel, bpy.types.Panel):
    bl_label = "Light"
    bl_context = "data"
    context_member = "light"

    def draw(self, context):
        layout = self.layout
        light = context.light
        layout.row().prop(light, "type", expand=True)
        layout.use_property_split = True
        if light.type not in {"POINT", "SUN", "AREA"}:
            layout.label(text="Whitted renders point, sun and area lights", icon="ERROR")
            return
        col = layout.column()
        col.prop(light, "color")
        col.prop(light, "energy")
        if light.type == "SUN":
            col.label(text="Parallel light along the object's -Z axis", icon="INFO")
            return
        if light.type == "AREA":
            col.prop(light, "shape")
            if light.shape not in {"SQUARE", "RECTANGLE"}:
                col.label(text="Area lights must be square or rectangular", icon="ERROR")
            elif light.shape == "SQUARE":
                col.prop(light, "size")
            else:
                col.prop(light, "size", text="Size X")
                col.prop(light, "size_y", text="Y")
        # intensity / (c0 + c1 d + c2 d^2): each coefficient under its own name
        attenuation = layout.column(align=True, heading="Attenuation")
        for index, label in enumerate(ATTENUATION_LABELS):
            attenuation.prop(light.whitted, "attenuation", index=index, text=label)
