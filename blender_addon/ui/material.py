"""Material Properties › Whitted Material: the report's material, or the Principled BSDF."""

import bpy

from ..export.material import find_node
from .base import WhittedPanel


class WHITTED_PT_material(WhittedPanel, bpy.types.Panel):
    bl_label = "Whitted Material"
    bl_context = "material"
    context_member = "material"

    def draw(self, context):
        layout = self.layout
        layout.use_property_split = True
        material = context.material
        settings = material.whitted
        principled = find_node(material, "BSDF_PRINCIPLED")
        # The Material Index pass's value (Cycles shows it in its material Settings)
        layout.prop(material, "pass_index")
        if principled is not None:
            layout.prop(settings, "use_whitted")
        if principled is not None and not settings.use_whitted:
            layout.label(text="From the Principled BSDF (base colour, metallic,", icon="INFO")
            layout.label(text="roughness, IOR, transmission)")
            return
        if principled is not None:
            layout.prop(principled.inputs["Base Color"], "default_value", text="Diffuse")
        else:
            layout.prop(material, "diffuse_color", text="Diffuse")
        layout.template_ID(settings, "image", open="image.open")
        for name in ("specular", "shininess", "reflectivity", "transparency"):
            layout.prop(settings, name)
        column = layout.column(align=True)
        column.active = settings.transparency > 0.0
        column.prop(settings, "outer_ior")
        column.prop(settings, "inner_ior")
