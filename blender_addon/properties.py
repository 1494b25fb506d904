"""Whitted's settings on Blender data: one PointerProperty `whitted` per data type.

Defaults come from what Blender already holds where it holds it (material base colour, light
colour and power), so an untouched scene renders sensibly.
"""

import bpy
from bpy.props import EnumProperty, FloatProperty, FloatVectorProperty, IntProperty, PointerProperty

SHAPE_ITEMS = [
    ("MESH", "Mesh", "Render the object's mesh (mesh rendering is not supported yet: skipped)"),
    (
        "SPHERE",
        "Sphere",
        "Render the exact sphere of radius 1 around the object origin, under the object's "
        "transform (matches Blender's UV sphere of radius 1)",
    ),
]


class WhittedObjectSettings(bpy.types.PropertyGroup):
    shape: EnumProperty(
        name="Shape",
        description="What Whitted renders for this object",
        items=SHAPE_ITEMS,
        default="MESH",
    )


class WhittedMaterialSettings(bpy.types.PropertyGroup):
    specular: FloatVectorProperty(
        name="Specular",
        description="Phong specular reflectance ks",
        subtype="COLOR",
        size=3,
        min=0.0,
        soft_max=1.0,
        default=(0.5, 0.5, 0.5),
    )
    shininess: FloatProperty(
        name="Shininess",
        description="Phong exponent p in ks (R.V)^p: larger is a smaller, sharper highlight",
        min=0.0,
        soft_max=1000.0,
        default=25.0,
    )


class WhittedLightSettings(bpy.types.PropertyGroup):
    attenuation: FloatVectorProperty(
        name="Attenuation",
        description=(
            "c0, c1, c2: light reaching distance d is intensity / (c0 + c1 d + c2 d^2); "
            "(0, 0, 1) is the physical inverse square law"
        ),
        size=3,
        min=0.0,
        default=(0.0, 0.0, 1.0),
    )


class WhittedSceneSettings(bpy.types.PropertyGroup):
    tile_size: IntProperty(
        name="Tile Size",
        description="Edge of the square tiles rendered in parallel and streamed to the image",
        min=8,
        max=1024,
        default=32,
    )


_owners = (
    (bpy.types.Object, WhittedObjectSettings),
    (bpy.types.Material, WhittedMaterialSettings),
    (bpy.types.Light, WhittedLightSettings),
    (bpy.types.Scene, WhittedSceneSettings),
)


def register():
    for owner, group in _owners:
        bpy.utils.register_class(group)
        owner.whitted = PointerProperty(type=group)


def unregister():
    for owner, group in reversed(_owners):
        del owner.whitted
        bpy.utils.unregister_class(group)
