"""World Properties › Whitted World: the World Model, what Whitted reads of the World, the
report's ambient term, and what Whitted cannot honour."""

import bpy

from ..export.material import find_node
from ..export.world import source, unsupported
from .base import WhittedPanel, draw_warnings


class WHITTED_PT_world(WhittedPanel, bpy.types.Panel):
    bl_label = "Whitted World"
    bl_context = "world"
    context_member = "world"

    def draw(self, context):
        layout = self.layout
        layout.use_property_split = True
        world = context.world
        layout.prop(world.whitted, "model")
        blender = world.whitted.model == "BLENDER"
        background = find_node(world, "BACKGROUND")
        label = "Color" if blender else "Background"
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
            layout.prop(context.scene.whitted, "environment_samples")
        layout.prop(world.whitted, "ambient")
        draw_warnings(layout, context, unsupported(world))
