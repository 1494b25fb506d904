"""Whitted's settings on Blender data: one PointerProperty `whitted` per data type.

Defaults come from what Blender already holds where it holds it (material base colour, light
colour and power), so an untouched scene renders sensibly.
"""

import bpy
from bpy.props import (
    BoolProperty,
    EnumProperty,
    FloatProperty,
    FloatVectorProperty,
    IntProperty,
    PointerProperty,
)

from . import shape_tags
from .core.scene import DEFAULT_PIXEL_SAMPLES, DEFAULT_SHADOW_SAMPLES


class WhittedObjectSettings(bpy.types.PropertyGroup):
    shape: EnumProperty(
        name="Shape",
        description=(
            "What Whitted renders for this mesh object: its triangles, or an exact shape under "
            "the object's transform (the mesh then only stands in for it in the viewport)"
        ),
        items=shape_tags.MENU_ITEMS,
        default="MESH",
    )
    major_radius: FloatProperty(
        name="Major Radius",
        description="Torus: radius of the ring, from the centre to the middle of the tube",
        min=0.0,
        default=1.0,
        unit="LENGTH",
    )
    minor_radius: FloatProperty(
        name="Minor Radius",
        description="Torus: radius of the tube",
        min=0.0,
        default=0.25,
        unit="LENGTH",
    )


class WhittedMaterialSettings(bpy.types.PropertyGroup):
    use_whitted: BoolProperty(
        name="Whitted Settings",
        description=(
            "Use the values below; off, the material renders from its Principled BSDF (base "
            "colour, metallic, roughness, IOR, transmission)"
        ),
        default=False,
    )
    reflectivity: FloatProperty(
        name="Reflectivity",
        description="Weight of the mirror reflection added to the surface colour (one more ray)",
        min=0.0,
        max=1.0,
        default=0.0,
    )
    transparency: FloatProperty(
        name="Transparency",
        description=(
            "Fraction of the colour that comes through the surface, refracted, with Fresnel "
            "reflection (two more rays at each hit)"
        ),
        min=0.0,
        max=1.0,
        default=0.0,
    )
    outer_ior: FloatProperty(
        name="Outer IOR",
        description="Index of refraction outside the surface (air: 1)",
        min=0.01,
        soft_max=3.0,
        default=1.0,
    )
    inner_ior: FloatProperty(
        name="Inner IOR",
        description="Index of refraction inside the surface (water 1.33, glass 1.5)",
        min=0.01,
        soft_max=3.0,
        default=1.5,
    )
    image: PointerProperty(
        name="Texture",
        description="Image replacing the diffuse colour, mapped by the shape's UVs",
        type=bpy.types.Image,
    )
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
    max_depth: IntProperty(
        name="Max Bounces",
        description=(
            "Reflection and refraction bounces after the camera ray; each level can double "
            "the rays of a pixel between facing mirrors or through glass"
        ),
        min=0,
        soft_max=16,
        max=64,
        default=5,
    )
    pixel_samples: IntProperty(
        name="Anti-Aliasing",
        description=(
            "n: each pixel averages n x n camera rays (the report used 3); render time grows "
            "as n squared"
        ),
        min=1,
        soft_max=8,
        max=32,
        default=DEFAULT_PIXEL_SAMPLES,
    )
    pixel_sampling: EnumProperty(
        name="Pattern",
        description="Where in the pixel the camera rays go",
        items=[
            ("GRID", "Grid", "At the centres of an n x n grid (the report's supersampling)"),
            ("JITTERED", "Jittered", "At a random point in each grid cell: noise, not aliasing"),
            ("RANDOM", "Random", "At independent random points in the pixel (for comparison)"),
        ],
        default="GRID",
    )
    shadow_sampling: EnumProperty(
        name="Shadow Pattern",
        description="Where on an area light the shadow rays go",
        items=[
            ("STRATIFIED", "Stratified", "One ray in each of equal cells of the light: less noise"),
            ("UNIFORM", "Uniform", "Independent random points (the report's way)"),
            ("HALTON", "Halton", "Low-discrepancy points, randomly shifted per shading point"),
        ],
        default="STRATIFIED",
    )
    seed: IntProperty(
        name="Seed",
        description="Selects the random numbers; the same seed gives the same picture",
        min=0,
        default=0,
    )
    shadow_samples: IntProperty(
        name="Soft Shadow Samples",
        description=(
            "Shadow rays per area light per shading point, stratified over the light; render "
            "time grows in proportion, noise falls as its square root"
        ),
        min=1,
        soft_max=256,
        default=DEFAULT_SHADOW_SAMPLES,
    )
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
