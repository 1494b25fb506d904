"""Render Properties, as Cycles lays them out: Sampling (with Shadows, World and Glossy under
it), Light Paths, Film, Performance. Labels are short enough for the Properties editor's
default width (a label of more than about nine characters is cut there, "Soft Shado…"); each
field's tooltip says the rest."""

import bpy

from ..engine import kernel_status
from .base import WhittedPanel


class _RenderPanel(WhittedPanel):
    bl_context = "render"

    def split_layout(self):
        layout = self.layout
        layout.use_property_split = True
        layout.use_property_decorate = False
        return layout


class WHITTED_PT_sampling(_RenderPanel, bpy.types.Panel):
    bl_label = "Sampling"

    def draw(self, context):
        layout = self.split_layout()
        warmup = kernel_status.panel_text()
        if warmup:  # the first-use compile, while it runs
            layout.label(text=warmup, icon="TIME")
        settings = context.scene.whitted
        column = layout.column(align=True)
        column.prop(settings, "pixel_samples", text="Samples")
        column.prop(settings, "pixel_sampling", text="Pattern")
        # As Cycles' Noise Threshold: a switch with its value beside it
        row = layout.row(heading="Adaptive")
        row.prop(settings, "use_adaptive_pixels", text="")
        value = row.row()
        value.active = settings.use_adaptive_pixels
        value.prop(settings, "adaptive_threshold", text="")
        layout.prop(settings, "seed")


class WHITTED_PT_sampling_shadows(_RenderPanel, bpy.types.Panel):
    bl_label = "Soft Shadows"
    bl_parent_id = "WHITTED_PT_sampling"

    def draw(self, context):
        layout = self.split_layout()
        settings = context.scene.whitted
        layout.prop(settings, "shadow_samples", text="Samples")
        layout.prop(settings, "shadow_sampling", text="Pattern")
        layout.prop(settings, "adaptive_shadows", text="Adaptive")


class WHITTED_PT_sampling_world(_RenderPanel, bpy.types.Panel):
    bl_label = "World Light"
    bl_parent_id = "WHITTED_PT_sampling"

    def draw(self, context):
        self.split_layout().prop(context.scene.whitted, "environment_samples", text="Samples")


class WHITTED_PT_sampling_glossy(_RenderPanel, bpy.types.Panel):
    bl_label = "Glossy Blur"
    bl_parent_id = "WHITTED_PT_sampling"

    def draw(self, context):
        self.split_layout().prop(context.scene.whitted, "glossy_samples", text="Samples")


class WHITTED_PT_light_paths(_RenderPanel, bpy.types.Panel):
    bl_label = "Light Paths"

    def draw(self, context):
        layout = self.split_layout()
        layout.prop(context.scene.whitted, "max_depth", text="Bounces")
        layout.prop(context.scene.whitted, "glass_shadows", text="Glass")


class WHITTED_PT_light_paths_caustics(_RenderPanel, bpy.types.Panel):
    bl_label = "Caustics"
    bl_parent_id = "WHITTED_PT_light_paths"

    def draw(self, context):
        layout = self.split_layout()
        settings = context.scene.whitted
        column = layout.column(heading="Caustics")
        column.prop(settings, "use_caustics_reflective", text="Mirrors")
        refractive = column.row()
        refractive.active = settings.glass_shadows == "BLOCKED"
        refractive.prop(settings, "use_caustics_refractive", text="Glass")
        photons = layout.column(heading="Photons")
        photons.prop(settings, "use_auto_photons", text="Automatic")
        count = photons.row()
        count.active = not settings.use_auto_photons
        count.prop(settings, "caustic_photons", text="Photons")


class WHITTED_PT_film(_RenderPanel, bpy.types.Panel):
    bl_label = "Film"

    def draw(self, context):
        # Film › Transparent, as Cycles and EEVEE name it, on the panel's whole width (its
        # label column would cut it)
        self.layout.prop(context.scene.render, "film_transparent", text="Transparent")


class WHITTED_PT_performance(_RenderPanel, bpy.types.Panel):
    bl_label = "Performance"
    bl_options = {"DEFAULT_CLOSED"}

    def draw(self, context):
        layout = self.split_layout()
        render = context.scene.render
        layout.prop(context.scene.whitted, "tile_size", text="Tiles")
        layout.prop(render, "threads_mode", text="Threads", expand=True)
        row = layout.row()
        row.enabled = render.threads_mode == "FIXED"
        row.prop(render, "threads", text="Count")


PANELS = (
    WHITTED_PT_sampling,
    WHITTED_PT_sampling_shadows,
    WHITTED_PT_sampling_world,
    WHITTED_PT_sampling_glossy,
    WHITTED_PT_light_paths,
    WHITTED_PT_light_paths_caustics,
    WHITTED_PT_film,
    WHITTED_PT_performance,
)
