"""Lights in Blender's units: what Cycles computes for point, spot, area and sun lights.

These are radiometric, unlike the report's lights (`core.model.lights`), which keep their
own attenuation model for CS488 scenes:

    SphereLight  a point light of `power` watts: radiant intensity power / 4 pi in every
                 direction; with a radius, a sphere (or, with Blender's Soft Falloff, a disk
                 turned towards the lit point) of radiance power / (4 pi^2 r^2)
    SpotLight    a SphereLight whose light is masked to a cone along its -Z axis
    PanelLight   a rectangle or ellipse, one-sided Lambertian emitter of `power` watts
                 (radiance power / (pi area)), shining towards -(edge_u x edge_v)
    SunLight     light from infinitely far, `irradiance` W/m^2 on a surface facing it,
                 from a cone of directions `angle` degrees across

A Lambertian surface of albedo kd lit by them has the radiance kd E / pi, E the irradiance,
as in Cycles. Mirrors and glass show them too (`core.kernels.emitters_seen`). Every light
can be kept from casting shadows, from lighting diffuse surfaces, from making highlights and
showing in mirrors, or from showing through glass (Blender's Cast Shadow and the light's
Diffuse, Glossy and Transmission Ray Visibility).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..checks import Vec3, check_choice, check_flag, check_light, check_number, check_vec3
from ..errors import SceneError
from .lights import check_parallelogram

PANEL_SHAPES = ("rectangle", "ellipse")
# How a sun's directions are spread: over a cone (Blender 4.0 on), or over a disk one unit
# away and normalised (Blender 3.x), which weights the cone's rim less
SUN_SAMPLINGS = ("cone", "disk")


@dataclass
class Emitter:
    """What every light in Blender's units has besides its geometry."""

    name: str = "Light"
    cast_shadow: bool = True  # Light > Cast Shadow
    diffuse: bool = True  # lights diffuse surfaces (Object > Visibility > Ray Visibility)
    specular: bool = True  # highlights, and seen in mirrors (the same panel's Glossy)
    transmission: bool = True  # seen through glass (the same panel's Transmission)

    def _check_switches(self, owner: str) -> None:
        for field in ("cast_shadow", "diffuse", "specular", "transmission"):
            check_flag(owner, field, getattr(self, field))


@dataclass
class SphereLight(Emitter):
    """A point light of `power` watts at `position`, of `radius` (0: a point).

    soft_falloff -- the radius is a disk turned towards each lit point (Blender's Soft
                    Falloff, on by default, and every point light before Blender 4.0), not
                    a sphere: a little less light close by, the same far away
    """

    position: Vec3 = (0.0, 0.0, 0.0)
    power: Vec3 = (1.0, 1.0, 1.0)
    radius: float = 0.0
    soft_falloff: bool = True

    def validate(self) -> None:
        owner = f"light '{self.name}'"
        check_vec3(owner, "position", self.position)
        check_light(owner, "power", self.power)
        check_number(owner, "radius", self.radius, low=0.0)
        check_flag(owner, "soft_falloff", self.soft_falloff)
        self._check_switches(owner)


@dataclass
class SpotLight(SphereLight):
    """A point light masked to a cone around its -Z axis.

    world_to_light  -- 3 x 3 rows taking a world direction into the light's own frame (the
                       inverse of its object's rotation and scale: a scaled spot light has an
                       elliptic cone)
    spot_size       -- the cone's full angle, degrees in (0, 180]
    blend           -- the share of the cone, from its rim inwards, over which the light
                       fades in smoothly (Blender's Spot Blend), in [0, 1]
    cosine_falloff  -- also scale by the cosine from the axis (Blender before 4.0)
    """

    world_to_light: tuple = ((1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0))
    spot_size: float = 45.0
    blend: float = 0.15
    cosine_falloff: bool = False

    def validate(self) -> None:
        super().validate()
        owner = f"spot light '{self.name}'"
        matrix = np.asarray(self.world_to_light, dtype=float)
        if matrix.shape != (3, 3) or not np.all(np.isfinite(matrix)):
            raise SceneError(owner, "world_to_light", "needs 3 x 3 finite numbers")
        if abs(np.linalg.det(matrix)) <= 1e-300:
            raise SceneError(owner, "world_to_light", "is singular (a scale of 0?)")
        check_number(owner, "spot_size", self.spot_size, low=0.0, high=180.0, low_open=True)
        check_number(owner, "blend", self.blend, low=0.0, high=1.0)
        check_flag(owner, "cosine_falloff", self.cosine_falloff)


@dataclass
class PanelLight(Emitter):
    """A flat light: the parallelogram centre + s edge_u + t edge_v, s, t in [-1/2, 1/2]
    (a rectangle), or the ellipse inscribed in it. It shines from one side only, towards
    -(edge_u x edge_v), as a Lambertian emitter of `power` watts."""

    centre: Vec3 = (0.0, 0.0, 0.0)
    edge_u: Vec3 = (1.0, 0.0, 0.0)
    edge_v: Vec3 = (0.0, 1.0, 0.0)
    shape: str = "rectangle"
    power: Vec3 = (1.0, 1.0, 1.0)

    def validate(self) -> None:
        owner = f"area light '{self.name}'"
        check_parallelogram(owner, self.centre, self.edge_u, self.edge_v)
        check_choice(owner, "shape", self.shape, PANEL_SHAPES)
        check_light(owner, "power", self.power)
        self._check_switches(owner)

    def area(self) -> float:
        parallelogram = float(np.linalg.norm(np.cross(self.edge_u, self.edge_v)))
        return parallelogram * (np.pi / 4.0 if self.shape == "ellipse" else 1.0)


@dataclass
class SunLight(Emitter):
    """Light travelling along `direction` from infinitely far: `irradiance` W/m^2 on a
    surface facing it, from directions within `angle` degrees across (0: parallel light,
    sharp shadows), spread as `sampling` says (SUN_SAMPLINGS)."""

    direction: Vec3 = (0.0, 0.0, -1.0)
    irradiance: Vec3 = (1.0, 1.0, 1.0)
    angle: float = 0.0
    sampling: str = "cone"

    def validate(self) -> None:
        owner = f"sun '{self.name}'"
        check_vec3(owner, "direction", self.direction, nonzero=True)
        check_light(owner, "irradiance", self.irradiance)
        check_number(owner, "angle", self.angle, low=0.0, high=180.0)
        check_choice(owner, "sampling", self.sampling, SUN_SAMPLINGS)
        self._check_switches(owner)


EMITTERS = (SphereLight, SpotLight, PanelLight, SunLight)
