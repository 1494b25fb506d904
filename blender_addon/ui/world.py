"""World Properties › Whitted World: the World Model, what Whitted reads of the World, the
report's ambient term, and what Whitted cannot honour."""

import bpy

from ..export.material import find_node
from ..export.world import source, unsupported
from .base import WhittedPanel, draw_warnings


class WHITTED_PT_world_preview(WhittedPanel, bpy.types.Panel):
    """World Properties › Preview: the World rendered by Whitted (bl_use_preview), as
    Cycles' own World preview panel shows it."""

    bl_label = "Preview"
    bl_context = "world"
    bl_options = {"DEFAULT_CLOSED"}
    context_member = "world"

    def draw(self, context):
        self.layout.template_preview(context.world)


class WHITTED_PT_world(WhittedPanel, bpy.types.Panel):
    bl_label = "Whitted World"
    bl_context = "world"
    context_member = "world"

    def draw(self, context):
        layout = self.layout
        layout.use_property_split = True
        world = context.world
        layout.prop(world.whitted, "model", text="Model")
        blender = world.whitted.model == "BLENDER"
        background = find_node(world, "BACKGROUND")
        label = "Color"
        if background is None:
            layout.prop(world, "color", text=label)
        else:
            fed = source(background.inputs[0])
            if fed is None:
                layout.prop(background.inputs[0], "default_value", text=label)
            else:
                layout.label(text=f"{label}: from '{fed[0].name}'", icon="NODE")
            layout.prop(background.inputs[1], "default_value", text="Strength")
        if blender:
            layout.prop(context.scene.whitted, "environment_samples", text="Samples")
        layout.prop(world.whitted, "ambient")
        draw_warnings(layout, context, unsupported(world))
