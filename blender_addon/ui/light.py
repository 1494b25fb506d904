"""Light Properties › Light, Whitted's: what it reads of every light type (in place of
Blender's Light, Area Shape and Spot Shape panels, so each field shows once), the light model,
the report's attenuation for CS488 lights, and what Whitted cannot honour."""

import bpy

from ..compat import cast_shadow_setting
from ..export.light import unsupported
from .base import WhittedPanel, draw_warnings

ATTENUATION_LABELS = ("Constant", "Linear", "Squared")  # "Quadratic" is cut at the default width


class WHITTED_PT_light(WhittedPanel, bpy.types.Panel):
    bl_label = "Light"
    bl_context = "data"
    context_member = "light"

    def draw(self, context):
        layout = self.layout
        light = context.light
        layout.row().prop(light, "type", expand=True)
        layout.use_property_split = True
        col = layout.column()
        col.prop(light, "color")
        if getattr(light, "use_temperature", None) is not None:
            row = col.row(heading="Temperature")
            row.prop(light, "use_temperature", text="")
            row.prop(light, "temperature", text="")
        col.prop(light, "energy")
        if hasattr(light, "exposure"):
            col.prop(light, "exposure")
        cs488 = light.type in {"POINT", "AREA"} and light.whitted.model == "CS488"
        if light.type in {"POINT", "AREA"}:
            col.prop(light.whitted, "model", text="Model")
        if light.type in {"POINT", "SPOT"}:
            col.prop(light, "shadow_soft_size", text="Radius")
            if hasattr(light, "use_soft_falloff") and not cs488:
                col.prop(light, "use_soft_falloff", text="Soft")
        elif light.type == "SUN":
            col.prop(light, "angle")
        else:
            self._draw_area(col, light, cs488)
        if light.type == "SPOT":
            col.prop(light, "spot_size", text="Size")
            col.prop(light, "spot_blend", text="Blend")
        # "Cast Shadow" is cut at the Properties editor's default width
        col.prop(*cast_shadow_setting(light), text="Shadow")
        if cs488:
            # intensity / (c0 + c1 d + c2 d^2): each coefficient under its own name
            attenuation = layout.column(align=True, heading="Falloff")
            for index, label in enumerate(ATTENUATION_LABELS):
                attenuation.prop(light.whitted, "attenuation", index=index, text=label)
        obj = context.object
        if obj is not None and obj.data == light:
            draw_warnings(layout, context, unsupported(obj))

    @staticmethod
    def _draw_area(col, light, cs488):
        col.prop(light, "shape")
        if light.shape in {"SQUARE", "DISK"}:
            col.prop(light, "size")
        else:
            col.prop(light, "size", text="Size X")
            col.prop(light, "size_y", text="Y")
        if not cs488:
            if hasattr(light, "normalize"):
                col.prop(light, "normalize")
            if hasattr(light, "spread"):
                col.prop(light, "spread")
