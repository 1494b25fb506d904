"""Material Properties › Whitted Material: what Whitted reads of the node tree and what it
cannot honour, or the report's material (Whitted Settings)."""

import bpy

from ..compat import node_tree_in_use
from ..core.model.shader import emits
from ..export.material import find_node, read_graph
from ..export.shader_nodes import closure_kinds
from .base import WhittedPanel, draw_warnings


class WHITTED_PT_material(WhittedPanel, bpy.types.Panel):
    bl_label = "Whitted Material"
    bl_context = "material"
    context_member = "material"

    def draw(self, context):
        layout = self.layout
        layout.use_property_split = True
        material = context.material
        settings = material.whitted
        # The Material Index pass's value (Cycles shows it in its material Settings)
        layout.prop(material, "pass_index", text="Index")
        # Labels of at most about eight characters: longer ones are cut at the Properties
        # editor's default width
        layout.row(heading="Model").prop(settings, "use_whitted", text="CS488")
        if not settings.use_whitted:
            self.draw_nodes(context, material)
            return
        principled = find_node(material, "BSDF_PRINCIPLED")
        if principled is not None:
            layout.prop(principled.inputs["Base Color"], "default_value", text="Diffuse")
        else:
            layout.prop(material, "diffuse_color", text="Diffuse")
        layout.template_ID(settings, "image", open="image.open")
        layout.prop(settings, "specular")
        layout.prop(settings, "shininess", text="Shine")
        layout.prop(settings, "reflectivity", text="Mirror")
        layout.prop(settings, "transparency", text="Refract")
        column = layout.column(align=True)
        column.active = settings.transparency > 0.0
        column.prop(settings, "outer_ior", text="IOR Out")
        column.prop(settings, "inner_ior", text="IOR In")

    def draw_nodes(self, context, material):
        layout = self.layout
        if node_tree_in_use(material) is None:
            layout.label(text="No nodes: its Viewport Display colour, as Lambert", icon="INFO")
            layout.prop(material, "diffuse_color", text="Color")
            return
        surface, problems, absorption = read_graph(material, textures=False)
        layout.label(text="Read from the node tree", icon="NODETREE")
        kinds = closure_kinds(surface) if surface is not None else []
        shown = ", ".join(kind.replace("_", " ") for kind in kinds) or "nothing (black)"
        layout.label(text="Renders as: " + shown)
        if max(absorption) > 0.0:
            per_metre = ", ".join(f"{a:.3g}" for a in absorption)
            layout.label(text=f"Inside: absorbs {per_metre} per metre (Volume Absorption)")
        if surface is not None and emits(surface):
            layout.prop(material.whitted, "emission_lights", text="Lights")
        draw_warnings(layout, context, [f"material '{material.name}': {p}" for p in problems])
