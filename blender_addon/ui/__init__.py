"""Panels, shown only while Whitted is the render engine, one module per Properties tab, and
the Add › Whitted menu (`add_menu`).

Blender's own panels for things Whitted reads as they are (output size, camera lens, light
colour and power, material slots) are opened to Whitted by adding it to their COMPAT_ENGINES.
"""

import bpy

from . import add_menu
from .base import ENGINE
from .light import WHITTED_PT_light
from .material import WHITTED_PT_material
from .object import WHITTED_PT_object_shape
from .render import WHITTED_PT_render
from .world import WHITTED_PT_world

# Blender panels whose settings Whitted honours as they are.
_BLENDER_PANELS = (
    "RENDER_PT_format",
    "RENDER_PT_frame_range",
    "RENDER_PT_output",
    "RENDER_PT_encoding",
    "RENDER_PT_post_processing",
    "RENDER_PT_color_management",
    "DATA_PT_context_camera",
    "DATA_PT_lens",
    "DATA_PT_camera",
    "DATA_PT_camera_display",
    "DATA_PT_context_light",
    "DATA_PT_light",
    "DATA_PT_EEVEE_light",
    "EEVEE_MATERIAL_PT_context_material",
    "MATERIAL_PT_preview",
    "WORLD_PT_context_world",
)


_classes = (
    WHITTED_PT_render,
    WHITTED_PT_object_shape,
    WHITTED_PT_material,
    WHITTED_PT_light,
    WHITTED_PT_world,
)


def _blender_panels():
    for name in _BLENDER_PANELS:
        panel = getattr(bpy.types, name, None)
        if panel is not None and hasattr(panel, "COMPAT_ENGINES"):
            yield panel


def register():
    add_menu.register()
    for cls in _classes:
        bpy.utils.register_class(cls)
    for panel in _blender_panels():
        panel.COMPAT_ENGINES.add(ENGINE)


def unregister():
    for panel in _blender_panels():
        panel.COMPAT_ENGINES.discard(ENGINE)
    for cls in reversed(_classes):
        bpy.utils.unregister_class(cls)
    add_menu.unregister()
