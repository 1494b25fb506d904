"""View Layer › Passes: Whitted's own switch beside Blender's pass switches."""

import bpy
from bpy.props import BoolProperty


class WhittedViewLayerSettings(bpy.types.PropertyGroup):
    use_pass_terms: BoolProperty(
        name="Whitted Terms",
        description=(
            "Combined split into Whitted's terms: ambient, direct diffuse, specular, and all "
            "that the first surface's reflection and refraction show; with Environment they "
            "add up to Combined"
        ),
        default=False,
    )
