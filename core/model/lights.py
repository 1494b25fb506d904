"""Lights: point lights with the report's attenuation, directional lights, area lights."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..checks import Vec3, check_light, check_vec3
from ..errors import SceneError


def check_parallelogram(owner: str, centre, edge_u, edge_v) -> None:
    """A light's centre and two edges that span an area (not parallel, neither zero)."""
    check_vec3(owner, "centre", centre)
    u = check_vec3(owner, "edge_u", edge_u, nonzero=True)
    v = check_vec3(owner, "edge_v", edge_v, nonzero=True)
    if np.linalg.norm(np.cross(u, v)) <= 1e-12 * np.linalg.norm(u) * np.linalg.norm(v):
        raise SceneError(owner, "edge_v", f"{edge_v} is parallel to edge_u {edge_u}")


def _check_attenuation(owner: str, attenuation) -> None:
    check_vec3(owner, "attenuation", attenuation, nonnegative=True, nonzero=True)


@dataclass
class PointLight:
    """A point light with the report's attenuation.

    position     -- where the light is
    intensity    -- linear RGB intensity, each channel >= 0
    attenuation  -- (c0, c1, c2): the light reaching distance d is intensity / (c0 + c1 d + c2 d^2);
                    each >= 0 and not all zero
    """

    position: Vec3 = (0.0, 0.0, 0.0)
    intensity: Vec3 = (1.0, 1.0, 1.0)
    attenuation: Vec3 = (1.0, 0.0, 0.0)
    name: str = "Light"

    def validate(self) -> None:
        owner = f"light '{self.name}'"
        check_vec3(owner, "position", self.position)
        check_light(owner, "intensity", self.intensity)
        _check_attenuation(owner, self.attenuation)


@dataclass
class DirectionalLight:
    """Parallel light from infinitely far away (the sun): no falloff, sharp shadows.

    direction  -- the direction the light travels, from the light onto the scene; non-zero
    intensity  -- linear RGB irradiance on a surface facing the light, each channel >= 0
    """

    direction: Vec3 = (0.0, 0.0, -1.0)
    intensity: Vec3 = (1.0, 1.0, 1.0)
    name: str = "Sun"

    def validate(self) -> None:
        owner = f"directional light '{self.name}'"
        check_vec3(owner, "direction", self.direction, nonzero=True)
        check_light(owner, "intensity", self.intensity)


@dataclass
class AreaLight:
    """A rectangular light: the parallelogram centre + s edge_u + t edge_v, s, t in [-1/2, 1/2].

    As in the report it acts as point lights of the full `intensity` spread evenly over the
    rectangle (the shading point sees their average), each with the report's attenuation; it
    lights both sides and is not itself visible. Soft shadows come from sampling it
    (`RenderSettings.shadow_samples`).

    centre       -- the centre of the rectangle
    edge_u       -- one full edge, as a vector (its length is the rectangle's width)
    edge_v       -- the other full edge; not parallel to edge_u
    intensity    -- linear RGB, each channel >= 0
    attenuation  -- (c0, c1, c2) as for `PointLight`
    """

    centre: Vec3 = (0.0, 0.0, 0.0)
    edge_u: Vec3 = (1.0, 0.0, 0.0)
    edge_v: Vec3 = (0.0, 1.0, 0.0)
    intensity: Vec3 = (1.0, 1.0, 1.0)
    attenuation: Vec3 = (1.0, 0.0, 0.0)
    name: str = "Area light"

    def validate(self) -> None:
        owner = f"area light '{self.name}'"
        check_parallelogram(owner, self.centre, self.edge_u, self.edge_v)
        check_light(owner, "intensity", self.intensity)
        _check_attenuation(owner, self.attenuation)
