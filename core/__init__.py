"""Whitted's renderer: scene model, packing, numba kernels and the tile driver. No bpy here.

from core import Camera, Material, PointLight, RenderSettings, Scene, Sphere, render
"""

from core.errors import SceneError
from core.image_io import save_png
from core.render import RenderOutput, RenderStats, Tile, render, split_into_tiles
from core.scene import Camera, Material, PointLight, RenderSettings, Scene, Sphere
from core.version import VERSION

__all__ = [
    "VERSION",
    "Camera",
    "Material",
    "PointLight",
    "RenderOutput",
    "RenderSettings",
    "RenderStats",
    "Scene",
    "SceneError",
    "Sphere",
    "Tile",
    "render",
    "save_png",
    "split_into_tiles",
]
