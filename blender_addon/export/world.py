"""The World -> the core's environment, background and ambient term.

World Properties > Whitted World > World Model says what the World is:

- Blender (the default): as in Cycles. The node tree is read from the active World Output's
  Surface: a Background node's Color times its Strength, the Color either a plain colour or
  an Environment Texture (equirectangular; Linear or Closest; its Vector from a Mapping node,
  Point, Texture, Vector or Normal type, fed by Generated coordinates or nothing). That
  environment is seen by every ray that leaves the scene and lights the scene through World
  Samples shadow rays per shading point. Without nodes (before Blender 5.0), the World's
  colour does the same. World Properties > Settings > Ray Visibility says which rays see it
  (camera, diffuse, glossy, transmission).
- CS488: the report's way. The Background colour (or the World's colour) is only what rays
  that leave the scene see; nothing is lit by it.

Either way the World's Ambient (Whitted's own) adds kd x ambient to every surface, unshadowed;
it is black unless set (the CS488 importer sets it from the script's ambient term).

Anything else in the tree (Sky Texture, Light Path tricks, a linked Strength, a Mix Shader)
is a warning naming the World, the node and the field, and what Whitted uses instead.
"""

from __future__ import annotations

import numpy as np
from mathutils import Euler

from .. import core
from ..compat import node_tree_in_use
from .material import find_node, image_texture

BLACK = (0.0, 0.0, 0.0)
RAY_VISIBILITY = ("camera", "diffuse", "glossy", "transmission")
SKY_ADVICE = " (render the sky to an image and use it in an Environment Texture)"


def convert(world, warn=lambda text: None, with_pixels: bool = True):
    """(environment or None, background colour, ambient colour) of `world` (may be None);
    `warn(text)` hears what Whitted cannot honour. Without pixels (a panel's check), an
    Environment Texture's image is not read and no environment is made of it."""
    if world is None:
        return None, BLACK, BLACK
    ambient = _bounded(world, tuple(float(c) for c in world.whitted.ambient), "Whitted > Ambient")
    if world.whitted.model == "CS488":
        return None, _bounded(world, _cs488_background(world), "Surface > Color"), ambient
    tree = node_tree_in_use(world)
    if tree is None:
        colour = _bounded(world, tuple(float(c) for c in world.color), "Viewport Display > Color")
        environment = core.Environment(colour=colour, name=world.name, **_ray_visibility(world))
        return environment, colour, ambient
    environment = _from_nodes(world, tree, warn, with_pixels)
    if environment is not None:
        _bounded(world, environment.colour, "Surface > Color x Strength")
        for name, visible in _ray_visibility(world).items():
            setattr(environment, name, visible)
    return environment, BLACK, ambient


def _bounded(world, colour: tuple, field: str) -> tuple:
    """`colour`, unless it is brighter than any light the renderer carries (Blender's fields
    reach 3.4e38, and Color x Strength 1e76: a white frame), refused in the panel's terms."""
    brightest = max(colour)
    if not brightest <= core.MAX_LIGHT:
        raise core.SceneError(
            f"world '{world.name}'",
            f"World Properties > {field}",
            f"gives {brightest:g}; Whitted takes a World of up to {core.MAX_LIGHT:g} (a clear "
            "sky is about 1): lower it",
        )
    return colour


def _cs488_background(world) -> tuple:
    background = find_node(world, "BACKGROUND")
    if background is not None:
        colour, strength = background.inputs[0].default_value, background.inputs[1].default_value
        return tuple(float(c) * strength for c in colour[:3])
    return tuple(float(c) for c in world.color)


def _ray_visibility(world) -> dict:
    """World Properties > Settings > Ray Visibility: which rays see the World (Cycles')."""
    visibility = getattr(world, "cycles_visibility", None)
    return {name: bool(getattr(visibility, name, True)) for name in RAY_VISIBILITY}


def source(socket):
    """The node and output socket feeding `socket`, through reroutes; None if unlinked."""
    while socket.is_linked:
        link = socket.links[0]
        node = link.from_node
        if node.type != "REROUTE":
            return node, link.from_socket
        socket = node.inputs[0]
    return None


def _active_output(tree):
    outputs = [n for n in tree.nodes if n.type == "OUTPUT_WORLD"]
    active = [n for n in outputs if n.is_active_output]
    return (active or outputs or [None])[0]


def _from_nodes(world, tree, warn, with_pixels) -> core.Environment | None:
    owner = f"world '{world.name}'"
    output = _active_output(tree)
    fed = None if output is None else source(output.inputs["Surface"])
    if fed is None:
        return None  # a World Output with nothing linked renders black in Cycles too
    node, _ = fed
    if node.type != "BACKGROUND":
        warn(
            f"{owner}: the World Output's Surface comes from '{node.name}' ({node.bl_label}); "
            "Whitted reads a Background node there: the World is black"
        )
        return None
    colour_socket, strength_socket = node.inputs["Color"], node.inputs["Strength"]
    strength = float(strength_socket.default_value)
    if strength_socket.is_linked:
        warn(
            f"{owner}: '{node.name}' Strength is linked, which Whitted does not read: "
            f"it uses the field's own value, {strength:g}"
        )
    colour = np.array(colour_socket.default_value[:3], float)
    fed = source(colour_socket)
    if fed is None:
        return core.Environment(colour=tuple(colour * strength), name=world.name)
    texture, _ = fed
    if texture.type != "TEX_ENVIRONMENT":
        warn(
            f"{owner}: '{node.name}' Color comes from '{texture.name}' ({texture.bl_label}), "
            "which Whitted does not read: it uses the Color field's own value"
            + (SKY_ADVICE if texture.type == "TEX_SKY" else "")
        )
        return core.Environment(colour=tuple(colour * strength), name=world.name)
    return _environment_texture(world, texture, strength, warn, with_pixels)


def _environment_texture(world, node, strength, warn, with_pixels) -> core.Environment | None:
    owner = f"world '{world.name}'"
    if node.image is None:
        warn(f"{owner}: '{node.name}' has no image; the World is black")
        return None
    if node.projection != "EQUIRECTANGULAR":
        warn(
            f"{owner}: '{node.name}' projection {node.projection.replace('_', ' ').title()} "
            "is read as Equirectangular"
        )
    interpolation = node.interpolation.lower()
    if interpolation not in {"linear", "closest"}:
        warn(f"{owner}: '{node.name}' interpolation {node.interpolation} is read as Linear")
        interpolation = "linear"
    transform = _vector_transform(world, node, warn)
    if not with_pixels:
        return None
    return core.Environment(
        colour=(strength,) * 3,
        image=image_texture(node.image, owner=owner),
        direction_from_world=transform,
        interpolation=interpolation,
        name=world.name,
    )


def _vector_transform(world, texture, warn) -> np.ndarray:
    """The 3 x 4 affine rows the texture's Vector input applies to a view direction."""
    owner = f"world '{world.name}'"
    identity = np.eye(3, 4)
    fed = source(texture.inputs["Vector"])
    if fed is None:
        return identity
    node, socket = fed
    if node.type == "TEX_COORD" and socket.name == "Generated":
        return identity
    if node.type != "MAPPING":
        warn(
            f"{owner}: '{texture.name}' Vector comes from '{node.name}' {socket.name}, which "
            "Whitted does not read: it looks the image up by the view direction"
        )
        return identity
    before = source(node.inputs["Vector"])
    if before is None or not (before[0].type == "TEX_COORD" and before[1].name == "Generated"):
        what = "nothing" if before is None else f"'{before[0].name}' {before[1].name}"
        warn(
            f"{owner}: '{node.name}' Vector comes from {what}; Whitted reads the view "
            "direction there (Texture Coordinate > Generated)"
        )
    return _mapping(world, node, warn)


def _mapping(world, node, warn) -> np.ndarray:
    """Blender's Mapping node as affine rows: Point R (S v) + L, Texture its inverse, Vector
    R (S v), Normal R (v / S) (the lookup normalises)."""
    values = {}
    for name in ("Location", "Rotation", "Scale"):
        socket = node.inputs.get(name)
        if socket is None:  # Vector-type mappings have no Location
            values[name] = np.zeros(3) if name != "Scale" else np.ones(3)
            continue
        if socket.is_linked:
            warn(
                f"world '{world.name}': '{node.name}' {name} is linked, which Whitted does "
                "not read: it uses the field's own value"
            )
        values[name] = np.array(socket.default_value, float)
    rotation = np.array(Euler(values["Rotation"], "XYZ").to_matrix(), float)
    scale, location = values["Scale"], values["Location"]
    kind = node.vector_type
    if kind == "TEXTURE":
        with np.errstate(divide="ignore"):
            linear = np.diag(np.where(scale != 0.0, 1.0 / scale, 0.0)) @ rotation.T
        return np.hstack([linear, (-linear @ location)[:, None]])
    if kind == "NORMAL":
        safe = np.where(scale != 0.0, scale, 1.0)
        return np.hstack([rotation @ np.diag(1.0 / safe), np.zeros((3, 1))])
    linear = rotation @ np.diag(scale)
    offset = location if kind == "POINT" else np.zeros(3)
    return np.hstack([linear, offset[:, None]])


def unsupported(world) -> list[str]:
    """The warnings a render of `world` gives, found without reading its images."""
    found = []
    convert(world, found.append, with_pixels=False)
    return found
