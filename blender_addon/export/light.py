"""Light objects -> core lights.

A light follows one of two models (Light Properties > Light > Light Model):

- Blender (the default): what Cycles computes, in Blender's units, for every light type:
  point (its Radius a sphere, or with Soft Falloff a disk turned to the lit point), spot
  (the same, masked by Spot Size and Blend), area (square, rectangle, disk, ellipse; one-sided,
  Normalize on and off) and sun (Angle). Colour x Power, times 2^Exposure and the
  Temperature's colour where the Blender version has them; Cast Shadow and the object's Ray
  Visibility (Diffuse, Glossy) count. Each version's own Cycles is matched
  (`compat.LIGHTS_BEFORE_4`), as measured side by side (tests/blender/test_cycles_lights.py).
- CS488: the report's point and area lights with their attenuation (c0 + c1 d + c2 d^2),
  for scenes imported from CS488 scripts. A point light's intensity is then colour x power /
  (4 pi^2): with attenuation (0, 0, 1) a white diffuse surface facing it is as bright as
  Cycles makes it.

What a light holds that Whitted cannot honour is a warning naming the light and the field
(`unsupported`), given with the render and drawn in the light's panel.
"""

from __future__ import annotations

import math

import numpy as np

from .. import core
from ..compat import LIGHTS_BEFORE_4, light_casts_shadow, node_tree_in_use

WATTS_TO_INTENSITY = 1.0 / (4.0 * math.pi**2)
FULL_SPREAD = math.pi


def convert(obj, matrix_world, warn=lambda text: None):
    """The core light of a light object placed by `matrix_world`; `warn(text)` hears what
    it cannot honour."""
    for text in unsupported(obj):
        warn(text)
    light = obj.data
    kind = light.type
    _check_power(obj)
    if kind in {"POINT", "AREA"} and light.whitted.model == "CS488":
        return (
            _point_light(obj, matrix_world) if kind == "POINT" else _area_light(obj, matrix_world)
        )
    matrix = np.array(matrix_world, float)
    if kind == "SUN":
        return _sun(obj, matrix)
    if kind == "AREA":
        return _panel(obj, matrix)
    return _sphere(obj, matrix)


def unsupported(obj) -> list[str]:
    """What Whitted does not render as Cycles would for this light object, each as a warning
    naming the light, the panel and field, and what Whitted does instead."""
    light, owner = obj.data, f"light '{obj.name}'"
    found = []
    cs488 = light.type in {"POINT", "AREA"} and light.whitted.model == "CS488"
    if cs488 and light.type == "POINT" and light.shadow_soft_size > 0.0:
        found.append(
            f"{owner}: Light > Radius {light.shadow_soft_size:g} m is not used by the CS488 "
            "light model, which is a point (sharp shadows); set Light Model to Blender for a "
            "soft light"
        )
    if cs488 and light.type == "AREA" and light.shape not in {"SQUARE", "RECTANGLE"}:
        found.append(
            f"{owner}: Light > Shape {light.shape.title()}: the CS488 light model has "
            "rectangles only, so Whitted lights with the rectangle around it; set Light Model "
            "to Blender for a disk or ellipse"
        )
    if (
        light.type == "AREA"
        and not cs488
        and getattr(light, "spread", FULL_SPREAD) < FULL_SPREAD - 1e-6
    ):
        found.append(
            f"{owner}: Light > Spread {math.degrees(light.spread):.0f}° is not modelled: "
            "Whitted's area lights shine over the full 180°"
        )
    if _nodes_change_the_light(light):
        found.append(
            f"{owner}: its shader nodes (Light > Nodes) are not read: Whitted lights with "
            "its Color and Power"
        )
    return found


def _nodes_change_the_light(light) -> bool:
    """The light's node tree does more than Blender's default (an Emission of white, strength
    1, into the Light Output), which every light has from Blender 5.2."""
    tree = node_tree_in_use(light)
    if tree is None:
        return False
    for node in tree.nodes:
        if node.type == "OUTPUT_LIGHT" or node.mute:
            continue
        if node.type != "EMISSION" or any(socket.is_linked for socket in node.inputs):
            return True
        colour, strength = node.inputs["Color"].default_value, node.inputs["Strength"].default_value
        if tuple(colour[:3]) != (1.0, 1.0, 1.0) or strength != 1.0:
            return True
    return False


def _check_power(obj) -> None:
    """Refuse a light brighter than the renderer carries (Color x Power reaches 1e76 in
    Blender's fields: a white frame), in the panel's terms."""
    brightest = float(np.max(blender_power(obj.data)))
    if not brightest <= core.MAX_LIGHT:
        field = "Strength" if obj.data.type == "SUN" else "Power"
        raise core.SceneError(
            f"light '{obj.name}'",
            f"Light Properties > Light > {field}",
            f"with its Color and Exposure gives {brightest:g}; Whitted takes lights of up to "
            f"{core.MAX_LIGHT:g}: lower it",
        )


def blender_power(light) -> np.ndarray:
    """Colour x Power (watts, or W/m^2 for a sun), times 2^Exposure and the Temperature's
    colour where the Blender version has them."""
    colour = np.array(light.color[:3], float)
    if getattr(light, "use_temperature", False):
        colour = colour * np.array(light.temperature_color[:3], float)
    return colour * light.energy * 2.0 ** getattr(light, "exposure", 0.0)


def _switches(obj) -> dict:
    """Cast Shadow, and whether the light reaches diffuse surfaces, makes highlights and is
    seen in mirrors, and is seen through glass (Object Properties > Visibility > Ray
    Visibility > Diffuse, Glossy, Transmission)."""
    return dict(
        name=obj.name,
        cast_shadow=light_casts_shadow(obj.data),
        diffuse=bool(getattr(obj, "visible_diffuse", True)),
        specular=bool(getattr(obj, "visible_glossy", True)),
        transmission=bool(getattr(obj, "visible_transmission", True)),
    )


def _sphere(obj, matrix: np.ndarray) -> core.SphereLight:
    """A point or spot light: its Radius a disk turned to the lit point with Soft Falloff
    (always before Blender 4.0), else a sphere."""
    light = obj.data
    fields = dict(
        position=tuple(matrix[:3, 3]),
        power=tuple(blender_power(light)),
        radius=float(light.shadow_soft_size),
        soft_falloff=LIGHTS_BEFORE_4 or bool(getattr(light, "use_soft_falloff", True)),
        **_switches(obj),
    )
    if light.type != "SPOT":
        return core.SphereLight(**fields)
    axes = matrix[:3, :3]
    if LIGHTS_BEFORE_4:
        # Cycles 3.x cones are round whatever the object's scale
        axes = axes / np.linalg.norm(axes, axis=0)
    _check_axes(obj, axes, "the spot light's cone")
    return core.SpotLight(
        **fields,
        world_to_light=tuple(map(tuple, np.linalg.inv(axes))),
        spot_size=math.degrees(light.spot_size),
        blend=float(light.spot_blend),
        cosine_falloff=LIGHTS_BEFORE_4,
    )


def _sun(obj, matrix: np.ndarray) -> core.SunLight:
    """A sun shining along the object's -Z axis: Strength is the irradiance on a surface
    facing it, from directions within its Angle."""
    light = obj.data
    _check_axes(obj, matrix[:3, :3], "the sun's direction")
    return core.SunLight(
        direction=tuple(-matrix[:3, 2]),
        irradiance=tuple(blender_power(light)),
        angle=math.degrees(light.angle),
        sampling="disk" if LIGHTS_BEFORE_4 else "cone",
        **_switches(obj),
    )


def _panel(obj, matrix: np.ndarray) -> core.PanelLight:
    """An area light on the object's x and y axes (scaled with it), shining towards its -Z.

    Cycles gives it radiance Power / (pi A): A the edges' lengths multiplied, times pi / 4
    for a disk or ellipse, or 1 m^2 with Normalize off (measured: Blender 3.x gives every
    area light pi / 4 of that); the core's panel of power p has radiance p / (pi area), so
    p = Power x area / A."""
    light = obj.data
    width, height = _panel_size(light)
    axes = matrix[:3, :3]
    _check_area(obj, width, height, axes)
    u, v = axes[:, 0] * width, axes[:, 1] * height
    if np.dot(np.cross(u, v), axes[:, 2]) < 0.0:
        v = -v  # a mirrored light still shines towards its own -Z, as in Cycles
    ellipse = light.shape in {"DISK", "ELLIPSE"}
    panel = core.PanelLight(
        centre=tuple(matrix[:3, 3]),
        edge_u=tuple(u),
        edge_v=tuple(v),
        shape="ellipse" if ellipse else "rectangle",
        power=(1.0, 1.0, 1.0),
        **_switches(obj),
    )
    if getattr(light, "normalize", True):
        cycles_area = np.linalg.norm(u) * np.linalg.norm(v) * (math.pi / 4.0 if ellipse else 1.0)
        if LIGHTS_BEFORE_4:
            cycles_area *= 4.0 / math.pi  # Cycles 3.x: every area light pi / 4 as bright
    else:
        cycles_area = 1.0
    panel.power = tuple(blender_power(light) * panel.area() / cycles_area)
    return panel


def _panel_size(light) -> tuple[float, float]:
    square = light.shape in {"SQUARE", "DISK"}
    return light.size, light.size if square else light.size_y


def _check_axes(obj, axes: np.ndarray, what: str) -> None:
    if not abs(np.linalg.det(axes)) > 1e-300:
        raise core.SceneError(
            f"light '{obj.name}'", "Object Properties > Transform > Scale",
            f"is 0 on an axis, which leaves {what} undefined; give every axis a non-zero scale",
        )  # fmt: skip


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
    one_size = obj.data.shape in {"SQUARE", "DISK"}
    for size, field in ((width, "Size" if one_size else "Size X"), (height, "Size Y")):
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


def _area_light(obj, matrix_world) -> core.AreaLight:
    """The report's area light: a rectangle on the object's x and y axes (scaled and
    rotated with it), lighting both sides, its intensity spread over it as points."""
    light = obj.data
    width, height = _panel_size(light)
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
