"""Light objects -> core lights.

A point light's intensity = colour * power / (4 pi^2). With attenuation (0, 0, 1) a white
diffuse surface facing the light then has the brightness Cycles gives it: a point light of
power P has radiant intensity P / (4 pi) W/sr and a Lambertian surface divides by pi. Area
lights likewise; a sun's irradiance is colour * strength / pi.
"""

from __future__ import annotations

import math

import numpy as np

from .. import core

WATTS_TO_INTENSITY = 1.0 / (4.0 * math.pi**2)


def convert(obj, matrix_world):
    """The core light of a light object placed by `matrix_world`, or None when Whitted cannot
    render it (a spot light, a disk or ellipse area light)."""
    kind = obj.data.type
    if kind == "POINT":
        return _point_light(obj, matrix_world)
    if kind == "SUN":
        return _sun_light(obj, matrix_world)
    if kind == "AREA":
        return _area_light(obj, matrix_world)
    return None


def _point_light(obj, matrix_world) -> core.PointLight:
    light = obj.data
    intensity = tuple(float(c) * light.energy * WATTS_TO_INTENSITY for c in light.color)
    return core.PointLight(
        position=tuple(matrix_world.translation),
        intensity=intensity,
        attenuation=tuple(light.whitted.attenuation),
        name=obj.name,
    )


def _check_area(obj, width: float, height: float, axes: np.ndarray) -> None:
    """Refuse a light with no area in the fields a user would change (Light > Size, the
    object's Scale), before the core's check names its edges instead."""
    owner = f"area light '{obj.name}'"
    square = obj.data.shape == "SQUARE"
    for size, field in ((width, "Size" if square else "Size X"), (height, "Size Y")):
        if not size > 0.0:
            raise core.SceneError(
                owner, f"Light Properties > Light > {field}",
                f"is {size:g}; an area light needs a size above 0",
            )  # fmt: skip
    u, v = axes[:, 0], axes[:, 1]
    # (a zero axis makes both sides 0)
    if np.linalg.norm(np.cross(u, v)) <= 1e-12 * np.linalg.norm(u) * np.linalg.norm(v):
        raise core.SceneError(
            owner, "Object Properties > Transform > Scale",
            "flattens the light to no area; give X and Y a non-zero scale",
        )  # fmt: skip


def _sun_light(obj, matrix_world) -> core.DirectionalLight:
    """A sun: light along the object's -Z axis, irradiance colour x strength / pi (a white
    diffuse surface facing it is then as bright as Cycles makes it)."""
    light = obj.data
    axes = np.array(matrix_world.to_3x3(), float)
    return core.DirectionalLight(
        direction=tuple(-axes[:, 2]),
        intensity=tuple(float(c) * light.energy / math.pi for c in light.color),
        name=obj.name,
    )


def _area_light(obj, matrix_world) -> core.AreaLight | None:
    """A square or rectangular area light, its edges along the object's x and y axes (so
    scaled and rotated with it), lighting both sides; None for disk and ellipse shapes."""
    light = obj.data
    if light.shape not in {"SQUARE", "RECTANGLE"}:
        return None
    width = light.size
    height = light.size if light.shape == "SQUARE" else light.size_y
    axes = np.array(matrix_world.to_3x3(), float)
    _check_area(obj, width, height, axes)
    intensity = tuple(float(c) * light.energy * WATTS_TO_INTENSITY for c in light.color)
    return core.AreaLight(
        centre=tuple(matrix_world.translation),
        edge_u=tuple(axes[:, 0] * width),
        edge_v=tuple(axes[:, 1] * height),
        intensity=intensity,
        attenuation=tuple(light.whitted.attenuation),
        name=obj.name,
    )
