"""Render Properties › Whitted: bounces, sampling, seed, tiles, threads, kernel warm-up."""

import bpy

from ..engine import kernel_status
from .base import WhittedPanel


class WHITTED_PT_render(WhittedPanel, bpy.types.Panel):
    bl_label = "Whitted"
    bl_context = "render"

    def draw(self, context):
        self.layout.use_property_split = True
        settings = context.scene.whitted
        for name in ("max_depth", "pixel_samples", "pixel_sampling", "shadow_samples"):
            self.layout.prop(settings, name)
        for name in ("shadow_sampling", "environment_samples", "glossy_samples", "seed",
                     "tile_size"):  # fmt: skip
            self.layout.prop(settings, name)
        warmup = kernel_status.status_text()
        if warmup:
            self.layout.label(text=warmup, icon="TIME")
        render = context.scene.render
        # Film > Transparent, as Cycles and EEVEE name it in their Film panels
        self.layout.prop(render, "film_transparent", text="Transparent Film")
        self.layout.prop(render, "threads_mode")
        row = self.layout.row()
        row.enabled = render.threads_mode == "FIXED"
        row.prop(render, "threads")
