"""Panels, shown only while Whitted is the render engine.

Blender's own panels for things Whitted reads as they are (output size, camera lens, light
colour and power, material slots) are opened to Whitted by adding it to their COMPAT_ENGINES.
"""

import bpy

from . import kernel_status
from .csg_export import OPERATIONS, boolean_modifiers, operand_objects
from .engine import WhittedRenderEngine
from .material_export import find_node

ENGINE = WhittedRenderEngine.bl_idname

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


class WhittedPanel:
    bl_space_type = "PROPERTIES"
    bl_region_type = "WINDOW"
    COMPAT_ENGINES = {ENGINE}
    # The context member (e.g. "material") the panel edits; it shows only when there is one
    context_member = None

    @classmethod
    def poll(cls, context):
        if context.engine not in cls.COMPAT_ENGINES:
            return False
        return cls.context_member is None or getattr(context, cls.context_member, None) is not None


class WHITTED_PT_render(WhittedPanel, bpy.types.Panel):
    bl_label = "Whitted"
    bl_context = "render"

    def draw(self, context):
        self.layout.use_property_split = True
        settings = context.scene.whitted
        for name in ("max_depth", "pixel_samples", "pixel_sampling", "shadow_samples"):
            self.layout.prop(settings, name)
        for name in ("shadow_sampling", "seed", "tile_size"):
            self.layout.prop(settings, name)
        warmup = kernel_status.status_text()
        if warmup:
            self.layout.label(text=warmup, icon="TIME")
        render = context.scene.render
        self.layout.prop(render, "threads_mode")
        row = self.layout.row()
        row.enabled = render.threads_mode == "FIXED"
        row.prop(render, "threads")


class WHITTED_PT_object_shape(WhittedPanel, bpy.types.Panel):
    bl_label = "Whitted Shape"
    bl_context = "object"

    @classmethod
    def poll(cls, context):
        return (
            super().poll(context) and context.object is not None and context.object.type == "MESH"
        )

    def draw(self, context):
        layout = self.layout
        layout.use_property_split = True
        obj = context.object
        layout.prop(obj.whitted, "shape")
        if obj.whitted.shape == "TORUS":
            layout.prop(obj.whitted, "major_radius")
            layout.prop(obj.whitted, "minor_radius")
        booleans = boolean_modifiers(obj)
        if booleans:
            box = layout.box()
            box.label(text="Renders as CSG, exactly:", icon="MOD_BOOLEAN")
            for modifier in booleans:
                operands = ", ".join(o.name for o in operand_objects(modifier)) or "(none)"
                box.label(text=f"{OPERATIONS[modifier.operation]} {operands}")


class WHITTED_PT_material(WhittedPanel, bpy.types.Panel):
    bl_label = "Whitted Material"
    bl_context = "material"
    context_member = "material"

    def draw(self, context):
        layout = self.layout
        layout.use_property_split = True
        material = context.material
        settings = material.whitted
        principled = find_node(material, "BSDF_PRINCIPLED")
        if principled is not None:
            layout.prop(settings, "use_whitted")
        if principled is not None and not settings.use_whitted:
            layout.label(text="From the Principled BSDF (base colour, metallic,", icon="INFO")
            layout.label(text="roughness, IOR, transmission)")
            return
        if principled is not None:
            layout.prop(principled.inputs["Base Color"], "default_value", text="Diffuse")
        else:
            layout.prop(material, "diffuse_color", text="Diffuse")
        layout.template_ID(settings, "image", open="image.open")
        for name in ("specular", "shininess", "reflectivity", "transparency"):
            layout.prop(settings, name)
        column = layout.column(align=True)
        column.active = settings.transparency > 0.0
        column.prop(settings, "outer_ior")
        column.prop(settings, "inner_ior")


class WHITTED_PT_light(WhittedPanel, bpy.types.Panel):
    bl_label = "Whitted Light"
    bl_context = "data"
    context_member = "light"

    def draw(self, context):
        layout = self.layout
        layout.use_property_split = True
        if context.light.type == "SUN":
            layout.label(text="Parallel light along the object's -Z axis", icon="INFO")
            return
        if context.light.type not in {"POINT", "AREA"}:
            layout.label(text="Whitted renders point, sun and area lights", icon="ERROR")
            return
        if context.light.type == "AREA" and context.light.shape not in {"SQUARE", "RECTANGLE"}:
            layout.label(text="Area lights must be square or rectangular", icon="ERROR")
        layout.prop(context.light.whitted, "attenuation")


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
    for cls in _classes:
        bpy.utils.register_class(cls)
    for panel in _blender_panels():
        panel.COMPAT_ENGINES.add(ENGINE)


def unregister():
    for panel in _blender_panels():
        panel.COMPAT_ENGINES.discard(ENGINE)
    for cls in reversed(_classes):
        bpy.utils.unregister_class(cls)
