"""Whitted's renderer: scene model, packing, numba kernels and the tile driver. No bpy here.

from . import Camera, Material, PointLight, RenderSettings, Scene, Sphere, render

The scene model is imported with the package; the driver (`core.driver`), and with it numba
and the kernels, only when one of its names is first used. A process that only builds or
checks scenes (a Lua script's child process, the Blender importer, the command line before
it renders) does not pay numba's import, a quarter of a second or more.
"""

import importlib

from .checks import MAX_EXTENT, MAX_LIGHT
from .errors import SceneError
from .image_io import save_png
from .model import (
    AreaLight,
    Box,
    Camera,
    Cone,
    Csg,
    Cylinder,
    DirectionalLight,
    Environment,
    Link,
    Material,
    Mesh,
    PanelLight,
    PointLight,
    RenderSettings,
    Scene,
    ShaderNode,
    Sphere,
    SphereLight,
    SpotLight,
    SunLight,
    Texture,
    Torus,
    TriangleMesh,
)
from .version import VERSION

__all__ = [
    "MAX_EXTENT",
    "MAX_LIGHT",
    "VERSION",
    "AreaLight",
    "Box",
    "Camera",
    "Cone",
    "Csg",
    "Cylinder",
    "DirectionalLight",
    "Environment",
    "Link",
    "Material",
    "Mesh",
    "PanelLight",
    "PointLight",
    "RenderOutput",
    "RenderSettings",
    "RenderStats",
    "Scene",
    "SceneError",
    "ShaderNode",
    "Sphere",
    "SphereLight",
    "SpotLight",
    "SunLight",
    "Texture",
    "Tile",
    "Torus",
    "TriangleMesh",
    "render",
    "save_png",
    "split_into_tiles",
]

# Names served by core.driver, imported on first use (PEP 562)
_FROM_DRIVER = {"RenderOutput", "RenderStats", "Tile", "render", "split_into_tiles"}


def __getattr__(name):
    if name in _FROM_DRIVER:
        driver = importlib.import_module(".driver", __name__)
        value = getattr(driver, name)
        globals()[name] = value  # found directly from now on
        return value
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
