"""Object › Whitted Shape: what a mesh object renders as."""

import bpy
from bpy.props import (
    EnumProperty,
    FloatProperty,
)

from . import shape_tags


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
