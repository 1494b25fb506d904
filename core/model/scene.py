"""The scene: a camera, shapes, lights, ambient and background, checked as a whole."""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ..checks import Vec3, check_light, valid_affine
from ..errors import SceneError
from .camera import Camera
from .emitters import EMITTERS
from .environment import Environment
from .lights import AreaLight, DirectionalLight, PointLight
from .shapes import Csg, Shape


@dataclass
class Scene:
    """Everything that is rendered.

    camera      -- the `Camera`
    shapes      -- the `Shape`s (Sphere, Box, Cylinder, Cone, Torus, Mesh, Csg)
    lights      -- `PointLight`s, `AreaLight`s and `DirectionalLight`s (the report's), and
                   lights in Blender's units (`core.model.emitters`)
    ambient     -- linear RGB ambient light, added as kd * ambient (the report's)
    background  -- linear RGB colour of rays that hit nothing, when there is no environment
    environment -- an `Environment` (Blender's World: seen behind the scene and lighting it),
                   or None
    """

    camera: Camera = field(default_factory=Camera)
    shapes: list = field(default_factory=list)
    lights: list = field(default_factory=list)
    ambient: Vec3 = (0.0, 0.0, 0.0)
    background: Vec3 = (0.0, 0.0, 0.0)
    environment: Environment | None = None

    def validate(self) -> None:
        self.camera.validate()
        for i, light in enumerate(self.lights):
            if not isinstance(light, (PointLight, AreaLight, DirectionalLight, *EMITTERS)):
                raise SceneError("scene", f"lights[{i}]", f"got {light!r}; need a light")
            light.validate()
        for i, shape in enumerate(self.shapes):
            if not isinstance(shape, Shape) or type(shape) is Shape:
                raise SceneError("scene", f"shapes[{i}]", f"got {shape!r}; need a shape")
        checked = self._checked_transforms()
        for shape in self.shapes:
            shape.validate(checked)
        check_light("scene", "ambient", self.ambient)
        check_light("scene", "background", self.background)
        if self.environment is not None:
            if not isinstance(self.environment, Environment):
                raise SceneError("scene", "environment", f"got {self.environment!r}")
            self.environment.validate()

    def object_and_material_names(self) -> tuple[list[str], list[str]]:
        """The names of the scene's shapes (a CSG tree named by its top node) and of every
        material, CSG operands' included: what object and material ids can name."""
        materials, stack = [], list(self.shapes)
        while stack:
            shape = stack.pop()
            if isinstance(shape, Csg):
                stack += [shape.left, shape.right]
            else:
                materials.append(shape.material.name)
        return [shape.name for shape in self.shapes], materials

    def _checked_transforms(self) -> set:
        """Ids of the shapes' transforms found valid, all checked at once (thousands of
        shapes would spend seconds one by one); the others are left to each shape's own
        check, which names it."""
        try:
            matrices = np.array([s.world_from_object for s in self.shapes], float)
        except (TypeError, ValueError):
            return set()
        if matrices.shape != (len(self.shapes), 4, 4):
            return set()
        ok = valid_affine(matrices)
        return {id(s.world_from_object) for s, good in zip(self.shapes, ok, strict=True) if good}
