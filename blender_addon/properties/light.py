"""Light Properties › Light: the report's attenuation, drawn by ui.light."""

import bpy
from bpy.props import (
    FloatVectorProperty,
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
