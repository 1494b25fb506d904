"""Whitted's settings on Blender data: one PointerProperty `whitted` per data type.

Defaults come from what Blender already holds where it holds it (material base colour, light
colour and power), so an untouched scene renders sensibly.
"""

import bpy
from bpy.props import PointerProperty

from .light import WhittedLightSettings
from .material import WhittedMaterialSettings
from .object import WhittedObjectSettings
from .scene import WhittedSceneSettings
from .view_layer import WhittedViewLayerSettings
from .world import WhittedWorldSettings

_owners = (
    (bpy.types.Object, WhittedObjectSettings),
    (bpy.types.Material, WhittedMaterialSettings),
    (bpy.types.Light, WhittedLightSettings),
    (bpy.types.Scene, WhittedSceneSettings),
    (bpy.types.ViewLayer, WhittedViewLayerSettings),
    (bpy.types.World, WhittedWorldSettings),
)


def register():
    for owner, group in _owners:
        bpy.utils.register_class(group)
        owner.whitted = PointerProperty(type=group)


def unregister():
    for owner, group in reversed(_owners):
        del owner.whitted
        bpy.utils.unregister_class(group)
