"""Material › Whitted Material: the CS488 scripts' gr.material values, drawn by ui.material."""

import bpy
from bpy.props import (
    BoolProperty,
    EnumProperty,
    FloatProperty,
    FloatVectorProperty,
    PointerProperty,
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
    emission_lights: EnumProperty(
        name="Emission Lights",
        description="Whether the material's emission lights other surfaces, sampled like an "
        "area light (meshes and evenly scaled spheres), or is only seen",
        items=[
            ("AUTO", "Auto", "As Cycles' Emission Sampling says: lights unless it is None"),
            ("ON", "On", "Lights the scene"),
            ("OFF", "Off", "Only seen, lighting nothing (cheaper)"),
        ],
        default="AUTO",
    )
    shininess: FloatProperty(
        name="Shininess",
        description="Phong exponent p in ks (R.V)^p: larger is a smaller, sharper highlight",
        min=0.0,
        soft_max=1000.0,
        default=25.0,
    )
