"""View Layer Properties › Passes: the passes Whitted makes, in Cycles' groups (Data, Light,
Cryptomatte), with the World's Mist Pass settings beside the Mist switch."""

import bpy

from .base import WhittedPanel


class WHITTED_PT_passes(WhittedPanel, bpy.types.Panel):
    bl_label = "Passes"
    bl_context = "view_layer"

    def draw(self, context):
        pass


class WHITTED_PT_passes_data(WhittedPanel, bpy.types.Panel):
    bl_label = "Data"
    bl_context = "view_layer"
    bl_parent_id = "WHITTED_PT_passes"

    def draw(self, context):
        layout = self.layout
        layout.use_property_split = True
        layout.use_property_decorate = False
        view_layer = context.view_layer
        column = layout.column(heading="Include", align=True)
        column.prop(view_layer, "use_pass_combined")
        column.prop(view_layer, "use_pass_z")
        column.prop(view_layer, "use_pass_mist")
        column.prop(view_layer, "use_pass_normal")
        column.prop(view_layer, "use_pass_position")
        column.prop(view_layer, "use_pass_uv")
        column = layout.column(heading="Indexes", align=True)
        column.prop(view_layer, "use_pass_object_index", text="Object")
        column.prop(view_layer, "use_pass_material_index", text="Material")
        world = context.scene.world
        if view_layer.use_pass_mist and world is not None:
            column = layout.column(align=True)
            column.prop(world.mist_settings, "start", text="Mist Start")
            column.prop(world.mist_settings, "depth", text="Depth")
            column.prop(world.mist_settings, "falloff")


class WHITTED_PT_passes_light(WhittedPanel, bpy.types.Panel):
    bl_label = "Light"
    bl_context = "view_layer"
    bl_parent_id = "WHITTED_PT_passes"

    def draw(self, context):
        layout = self.layout
        layout.use_property_split = True
        layout.use_property_decorate = False
        view_layer = context.view_layer
        column = layout.column(heading="Diffuse", align=True)
        column.prop(view_layer, "use_pass_diffuse_color", text="Color")
        column = layout.column(heading="Other", align=True)
        column.prop(view_layer, "use_pass_shadow")
        column.prop(view_layer, "use_pass_emit", text="Emission")
        # Labels of at most about nine characters: longer ones are cut at the default width
        column.prop(view_layer, "use_pass_environment", text="World")
        column.prop(view_layer.whitted, "use_pass_terms", text="Terms")


class WHITTED_PT_passes_crypto(WhittedPanel, bpy.types.Panel):
    bl_label = "Cryptomatte"
    bl_context = "view_layer"
    bl_parent_id = "WHITTED_PT_passes"

    def draw(self, context):
        layout = self.layout
        layout.use_property_split = True
        layout.use_property_decorate = False
        view_layer = context.view_layer
        column = layout.column(heading="Include", align=True)
        column.prop(view_layer, "use_pass_cryptomatte_object", text="Object")
        column.prop(view_layer, "use_pass_cryptomatte_material", text="Material")
        layout.prop(view_layer, "pass_cryptomatte_depth", text="Levels")


PANELS = (WHITTED_PT_passes, WHITTED_PT_passes_data, WHITTED_PT_passes_light,
          WHITTED_PT_passes_crypto)  # fmt: skip
