"""World Properties › Whitted World: how the World lights the scene, and the CS488 model's
ambient term, drawn by ui.world."""

import bpy
from bpy.props import EnumProperty, FloatVectorProperty

MODELS = [
    (
        "BLENDER",
        "Blender",
        "As Cycles: the World's colour or Environment Texture is seen behind the scene and in "
        "mirrors and glass, and lights the scene from every direction (occluded, soft)",
    ),
    (
        "CS488",
        "CS488",
        "The course project's: the World's colour is only the background; the Ambient colour "
        "below is added to every surface as kd x ambient",
    ),
]


class WhittedWorldSettings(bpy.types.PropertyGroup):
    model: EnumProperty(
        name="World Model",
        description="What the World does besides being seen",
        items=MODELS,
        default="BLENDER",
    )
    ambient: FloatVectorProperty(
        name="Ambient",
        description=(
            "A constant light added to every surface as its diffuse colour times this, "
            "unshadowed: lifts the shadows evenly (black: none)"
        ),
        subtype="COLOR",
        size=3,
        min=0.0,
        soft_max=1.0,
        default=(0.0, 0.0, 0.0),
    )
