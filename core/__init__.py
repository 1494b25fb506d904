"""Whitted's renderer: scene model, packing, numba kernels and the tile driver. No bpy here.

from . import Camera, Material, PointLight, RenderSettings, Scene, Sphere, render
"""

from .errors import SceneError
from .image_io import save_png
from .render import RenderOutput, RenderStats, Tile, render, split_into_tiles
from .scene import (
    AreaLight,
    Box,
    Camera,
    Cone,
    Csg,
    Cylinder,
    DirectionalLight,
    Material,
    Mesh,
    PointLight,
    RenderSettings,
    Scene,
    Sphere,
    Texture,
    Torus,
    TriangleMesh,
)
from .version import VERSION

__all__ = [
    "VERSION",
    "AreaLight",
    "Box",
    "Camera",
    "Cone",
    "Csg",
    "Cylinder",
    "DirectionalLight",
    "Material",
    "Mesh",
    "PointLight",
    "RenderOutput",
    "RenderSettings",
    "RenderStats",
    "Scene",
    "SceneError",
    "Sphere",
    "Texture",
    "Tile",
    "Torus",
    "TriangleMesh",
    "render",
    "save_png",
    "split_into_tiles",
]
