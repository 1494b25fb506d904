"""Panels, shown only while Whitted is the render engine, one module per Properties tab, and
the Add › Whitted menu (`add_menu`).

Blender's own panels for things Whitted reads as they are (output size, camera lens and depth
of field, object visibility, mesh data, material slots) are opened to Whitted by adding it
to their COMPAT_ENGINES (`blender_panels`).
"""

import bpy

from . import add_menu
from .base import ENGINE
from .light import WHITTED_PT_light
from .material import WHITTED_PT_material
from .object import WHITTED_PT_object_ray_visibility, WHITTED_PT_object_shape
from .render import PANELS as RENDER_PANELS
from .view_layer import PANELS as VIEW_LAYER_PANELS
from .world import WHITTED_PT_world, WHITTED_PT_world_preview

# Blender's panels open to Whitted, as Cycles opens them: every panel open to BLENDER_RENDER
# (the engine-independent ones: output, format, frame range, camera lens, object visibility,
# mesh data, modifiers' physics, metadata...), less those whose settings Whitted ignores,
# plus a few made for EEVEE whose settings Whitted reads as they are
_IGNORED_PREFIXES = (
    "RENDER_PT_freestyle", "VIEWLAYER_PT_freestyle", "MATERIAL_PT_freestyle",  # no Freestyle
    "RENDER_PT_gpencil", "RENDER_PT_grease_pencil", "RENDER_PT_simplify_greasepencil",
    "DATA_PT_lightprobe", "DATA_PT_context_lightprobe",  # no light probes
)  # fmt: skip
_IGNORED = {
    "RENDER_PT_stereoscopy", "RENDER_PT_output_views", "DATA_PT_camera_stereoscopy",  # one view
    "DATA_PT_falloff_curve",  # EEVEE's
    "DATA_PT_spot",  # Whitted's own Light panel draws the spot's size and blend
    "DATA_PT_volume_render",  # nor volumes
    "NODE_DATA_PT_light",  # a light's node tree is not read
    # Whitted's own Light panel draws the type, colour, power and area shape it reads, once
    "DATA_PT_light", "DATA_PT_area",
}  # fmt: skip
_ALSO_SHOWN = (
    "DATA_PT_camera_dof",  # focus object or distance, f-stop: Whitted's thin lens
    "DATA_PT_camera_dof_aperture",
    "EEVEE_MATERIAL_PT_context_material",  # the material slots
    "MATERIAL_PT_preview",  # Whitted renders the preview (bl_use_preview)
)


def blender_panels():
    """The Blender panel classes shown to Whitted, whatever this Blender version has."""
    for name in dir(bpy.types):
        panel = getattr(bpy.types, name, None)
        engines = getattr(panel, "COMPAT_ENGINES", None)
        if not isinstance(engines, set) or name.startswith("WHITTED_"):
            continue
        if name in _ALSO_SHOWN or (
            "BLENDER_RENDER" in engines
            and name not in _IGNORED
            and not name.startswith(_IGNORED_PREFIXES)
        ):
            yield panel


_opened = []  # the panels register() opened, to close on unregister

_classes = (
    *RENDER_PANELS,
    WHITTED_PT_object_shape,
    WHITTED_PT_object_ray_visibility,
    WHITTED_PT_material,
    WHITTED_PT_light,
    WHITTED_PT_world_preview,
    WHITTED_PT_world,
    *VIEW_LAYER_PANELS,
)


def register():
    add_menu.register()
    for cls in _classes:
        bpy.utils.register_class(cls)
    _opened.clear()
    for panel in blender_panels():
        if ENGINE not in panel.COMPAT_ENGINES:
            panel.COMPAT_ENGINES.add(ENGINE)
            _opened.append(panel)


def unregister():
    for panel in _opened:
        panel.COMPAT_ENGINES.discard(ENGINE)
    _opened.clear()
    for cls in reversed(_classes):
        bpy.utils.unregister_class(cls)
    add_menu.unregister()
