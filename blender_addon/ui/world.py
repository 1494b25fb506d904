"""World Properties › Whitted World: the one colour that is ambient and background."""

import bpy

from ..export.material import find_node
from .base import WhittedPanel


class WHITTED_PT_world(WhittedPanel, bpy.types.Panel):
    bl_label = "Whitted World"
    bl_context = "world"
    context_member = "world"

    def draw(self, context):
        layout = self.layout
        layout.use_property_split = True
        world = context.world
        background = find_node(world, "BACKGROUND")
        if background is not None:
            layout.prop(background.inputs[0], "default_value", text="Ambient and Background")
            layout.prop(background.inputs[1], "default_value", text="Strength")
        else:
            layout.prop(world, "color", text="Ambient and Background")
