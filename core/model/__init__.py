"""The scene model: small dataclasses a person can read, and their validation, a module each.

    camera.py     Camera
    lights.py     PointLight, DirectionalLight, AreaLight: the report's lights
    emitters.py   SphereLight, SpotLight, PanelLight, SunLight: lights in Blender's units
    environment.py  Environment: Blender's World, a colour or an equirectangular image
    materials.py  Material, Texture
    shader.py     ShaderNode, Link: Blender's node graphs, run per hit
    shapes.py     Sphere, Box, Cylinder, Cone, Torus, TriangleMesh and Mesh, Csg
    scene.py      Scene
    settings.py   RenderSettings and its defaults and limits

Everything here is plain Python and numpy; nothing is Blender-specific, and nothing imports
numba. Exporters (the Blender add-on, the Lua loader) build these objects; `core.compile` turns
them into the flat arrays the kernels read. Validation lives with the classes, so every front
end gets the same `SceneError` naming the object and the field.

Conventions: world space is z-up like Blender's; colours are linear RGB; distances are in
scene units; angles are in degrees.
"""

from .camera import Camera
from .emitters import PanelLight, SphereLight, SpotLight, SunLight
from .environment import Environment
from .lights import AreaLight, DirectionalLight, PointLight
from .materials import Material, Texture
from .scene import Scene
from .settings import RenderSettings
from .shader import Link, ShaderNode
from .shapes import Box, Cone, Csg, Cylinder, Mesh, Shape, Sphere, Torus, TriangleMesh

__all__ = [
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
    "RenderSettings",
    "Scene",
    "ShaderNode",
    "Shape",
    "Sphere",
    "SphereLight",
    "SpotLight",
    "SunLight",
    "Texture",
    "Torus",
    "TriangleMesh",
]
