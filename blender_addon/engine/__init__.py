"""The RenderEngine Blender knows as "Whitted". Each of its jobs has a module of its own:
`final` (F12 and `blender -b`), with room beside it for the viewport and previews;
`kernel_status` shows the kernel warm-up in Blender's windows.
"""

import bpy

from . import final


class WhittedRenderEngine(bpy.types.RenderEngine):
    bl_idname = "WHITTED"
    bl_label = "Whitted"
    bl_use_preview = False

    def render(self, depsgraph):
        final.render(self, depsgraph)


def register():
    bpy.utils.register_class(WhittedRenderEngine)


def unregister():
    bpy.utils.unregister_class(WhittedRenderEngine)
