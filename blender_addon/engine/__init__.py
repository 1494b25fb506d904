"""The RenderEngine Blender knows as "Whitted". Each of its jobs has a module of its own:
`final` (F12, `blender -b`, and material and world previews), `viewport` (a 3D view's
Rendered shading, drawn by `view_texture`); `kernel_status` shows the kernel warm-up in
Blender's windows.
"""

import bpy

from . import final, viewport


class WhittedRenderEngine(bpy.types.RenderEngine):
    bl_idname = "WHITTED"
    bl_label = "Whitted"
    # Material and world thumbnails and the Preview panel render with Whitted (`is_preview`)
    bl_use_preview = True
    # Material Preview shading draws with EEVEE, so the objects show there; Rendered is ours
    bl_use_eevee_viewport = True

    def __init__(self, *args, **kwargs):
        super().__init__(*args, **kwargs)
        self.whitted_viewport = None

    def __del__(self):
        # Blender frees the engine when its 3D view leaves Rendered shading: the view's
        # render thread stops here (within a pixel's rays), not at the end of its pass
        viewport.free(self)

    def render(self, depsgraph):
        final.render(self, depsgraph)

    def update_render_passes(self, scene=None, renderlayer=None):
        final.register_passes(self, scene, renderlayer)

    def view_update(self, context, depsgraph):
        viewport.view_update(self, context, depsgraph)

    def view_draw(self, context, depsgraph):
        viewport.view_draw(self, context, depsgraph)


def register():
    bpy.utils.register_class(WhittedRenderEngine)


def unregister():
    viewport.unregister()
    bpy.utils.unregister_class(WhittedRenderEngine)
