"""Light Properties › Light: which light model a light follows, and the attenuation of those
that follow the CS488 scripts' model, drawn by ui.light."""

import bpy
from bpy.props import (
    EnumProperty,
    FloatVectorProperty,
)

MODELS = [
    (
        "BLENDER",
        "Blender",
        "As Cycles lights it: power in watts, the inverse square law, soft shadows from the "
        "light's Radius, Angle or area, area lights shining from their -Z side",
    ),
    (
        "CS488",
        "CS488",
        "The course project's lights: intensity / (c0 + c1 d + c2 d^2) with the attenuation "
        "below, area lights shining both ways as points spread over the rectangle",
    ),
]


class WhittedLightSettings(bpy.types.PropertyGroup):
    model: EnumProperty(
        name="Light Model",
        description="How the light's brightness falls off with distance",
        items=MODELS,
        default="BLENDER",
    )
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
