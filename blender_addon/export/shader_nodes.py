"""A material's node tree read as Cycles reads it, into `Lobes` (shader_lobes has the terms).

From the active Material Output's Surface socket down: Mix Shader and Add Shader combine
what their inputs make; each BSDF, Emission and Holdout node adds its lobes
(`SHADERS`). Inputs are read as constants: an unlinked socket's value, a Value or RGB node,
and an Image Texture feeding a diffuse colour. Anything else is named in the material's
warning with what was used in its place.
"""

from __future__ import annotations

import numpy as np

from ..compat import PRINCIPLED_LAYERED
from .shader_graph import Feed, feed_of, node_label, output_node
from .shader_lobes import Lobes

# Mix Shader factors and weights below this add nothing (Cycles' closure cutoff)
WEIGHT_CUTOFF = 1e-5


class MaterialReader:
    """Reads one material's tree; `problems` lists what it could not honour, each once."""

    def __init__(self, material):
        self.material = material
        self.problems: list[str] = []

    def note(self, text: str) -> None:
        if text not in self.problems:
            self.problems.append(text)

    def read(self, tree) -> Lobes:
        output = output_node(tree)
        if output is None:
            self.note("its node tree has no Material Output: rendered black")
            return Lobes()
        for name in ("Volume", "Displacement"):
            socket = output.inputs.get(name)
            if socket is not None and socket.is_linked:
                used = "the surface's own normal" if name == "Displacement" else "nothing"
                self.note(f"the Material Output's {name} is not rendered (used: {used})")
        return self.shader(feed_of(output.inputs["Surface"]), 1.0)

    def shader(self, feed: Feed, weight: float) -> Lobes:
        if feed.node is None or weight < WEIGHT_CUTOFF:
            return Lobes()  # an unlinked shader socket adds nothing, as in Cycles
        node = feed.node
        if getattr(node, "mute", False):
            # A muted node passes its first linked shader input through
            for socket in node.inputs:
                if socket.type == "SHADER" and socket.is_linked:
                    return self.shader(feed_of(socket, feed.groups), weight)
            return Lobes()
        read = SHADERS.get(node.type)
        if read is None:
            self.note(f"node {node_label(node)} is not a shader Whitted renders (used: black)")
            return Lobes()
        return read(self, node, feed.groups, weight)

    def number(self, node, groups, *names, default=0.0) -> float:
        """A float input's value by the first of `names` the node has."""
        socket = _input(node, names)
        if socket is None:
            return default
        value = self._constant(socket, groups, node)
        return float(value if np.ndim(value) == 0 else np.mean(np.asarray(value)[:3]))

    def colour(self, node, groups, *names, textures=False):
        """(RGB, Image Texture's image or None) of a colour input; an image only where
        `textures` (a diffuse colour)."""
        socket = _input(node, names)
        if socket is None:
            return np.ones(3), None
        feed = feed_of(socket, groups)
        if textures and feed.node is not None and feed.node.type == "TEX_IMAGE":
            image = feed.node.image
            if image is not None:
                return np.ones(3), image
        value = self._constant(socket, groups, node)
        rgb = np.asarray(value, float).ravel()
        return (np.repeat(rgb[:1], 3) if rgb.size == 1 else rgb[:3]), None

    def linked(self, node, groups, name, what: str) -> None:
        """Note an input Whitted does not read, when something feeds it."""
        socket = node.inputs.get(name)
        if socket is not None and feed_of(socket, groups).node is not None:
            self.note(f"{node_label(node)}'s {name} is not read (used: {what})")

    def _constant(self, socket, groups, consumer):
        feed = feed_of(socket, groups)
        if feed.node is None:
            return _value(feed.socket)
        if feed.node.type in ("VALUE", "RGB"):
            return _value(feed.socket)
        fallback = _value(socket)
        shown = _shown(fallback)
        self.note(
            f"node {node_label(feed.node)} feeding {node_label(consumer)}'s {socket.name} is "
            f"not evaluated (used: its value {shown})"
        )
        return fallback


def _input(node, names):
    for name in names:
        socket = node.inputs.get(name)
        if socket is not None and getattr(socket, "enabled", True):
            return socket
    return None


def _value(socket):
    value = getattr(socket, "default_value", 0.0)
    try:
        return tuple(value)
    except TypeError:
        return value


def _shown(value) -> str:
    if np.ndim(value) == 0:
        return f"{float(value):g}"
    return ", ".join(f"{float(v):g}" for v in list(value)[:3])


def _clamped(value: float) -> float:
    return min(max(value, 0.0), 1.0)


# The shader nodes, by node.type: each reads its node into weighted lobes


def _mix(reader, node, groups, weight):
    factor = _clamped(reader.number(node, groups, "Fac"))
    lobes = reader.shader(feed_of(node.inputs[1], groups), weight * (1.0 - factor))
    lobes.add(reader.shader(feed_of(node.inputs[2], groups), weight * factor))
    return lobes


def _add(reader, node, groups, weight):
    lobes = reader.shader(feed_of(node.inputs[0], groups), weight)
    lobes.add(reader.shader(feed_of(node.inputs[1], groups), weight))
    return lobes


def _diffuse(reader, node, groups, weight):
    colour, image = reader.colour(node, groups, "Color", textures=True)
    if reader.number(node, groups, "Roughness") > 0.0:
        reader.note(f"{node_label(node)}'s Roughness is not modelled (used: Lambert, 0)")
    reader.linked(node, groups, "Normal", "the surface's own normal")
    lobes = Lobes()
    lobes.add_diffuse(weight, np.maximum(colour, 0.0), image)
    return lobes


def _glossy(reader, node, groups, weight):
    colour, _ = reader.colour(node, groups, "Color")
    roughness = _clamped(reader.number(node, groups, "Roughness"))
    reader.linked(node, groups, "Normal", "the surface's own normal")
    lobes = Lobes()
    tint = np.maximum(colour, 0.0)
    lobes.add_mirror(weight, tint, tint, roughness)
    return lobes


def _metallic(reader, node, groups, weight):
    """Blender 4.3's Metallic BSDF: F82 Tint (Base Color to Edge Tint), as Schlick's."""
    colour, _ = reader.colour(node, groups, "Base Color")
    edge, _ = reader.colour(node, groups, "Edge Tint")
    if getattr(node, "fresnel_type", "F82") != "F82":
        reader.note(f"{node_label(node)}'s Physical Conductor Fresnel (used: F82 Tint)")
    roughness = _clamped(reader.number(node, groups, "Roughness"))
    lobes = Lobes()
    lobes.add_mirror(weight, np.clip(colour, 0.0, 1.0), np.clip(edge, 0.0, 1.0), roughness)
    return lobes


def _glass(reader, node, groups, weight, fresnel=1.0):
    colour, _ = reader.colour(node, groups, "Color")
    ior = max(reader.number(node, groups, "IOR", default=1.45), 1e-5)
    reader.linked(node, groups, "Normal", "the surface's own normal")
    tint = np.maximum(colour, 0.0)
    lobes = Lobes()
    lobes.add_glass(weight, ior, tint * fresnel, tint, fresnel)
    return lobes


def _refraction(reader, node, groups, weight):
    return _glass(reader, node, groups, weight, fresnel=0.0)


def _transparent(reader, node, groups, weight):
    colour, _ = reader.colour(node, groups, "Color")
    if np.ptp(colour) > 1e-6:
        reader.note(
            f"{node_label(node)}'s colour tints what is seen through it, not the shadows it "
            f"casts (used: its mean, {float(np.mean(colour)):.3g}, for shadows)"
        )
    lobes = Lobes()
    lobes.transparent += weight * np.clip(colour, 0.0, 1.0)
    return lobes


def _emission(reader, node, groups, weight):
    colour, _ = reader.colour(node, groups, "Color")
    strength = reader.number(node, groups, "Strength", default=1.0)
    lobes = Lobes()
    lobes.emission += weight * np.maximum(colour * strength, 0.0)
    return lobes


def _holdout(reader, node, groups, weight):
    lobes = Lobes()
    lobes.holdout += weight
    return lobes


def _translucent(reader, node, groups, weight):
    reader.note(f"{node_label(node)}: light through thin surfaces is not computed (used: black)")
    return Lobes()


def _principled(reader, node, groups, weight):
    from .principled import principled_lobes

    return principled_lobes(reader, node, groups, weight, PRINCIPLED_LAYERED)


SHADERS = {
    "MIX_SHADER": _mix,
    "ADD_SHADER": _add,
    "BSDF_PRINCIPLED": _principled,
    "BSDF_DIFFUSE": _diffuse,
    "BSDF_GLOSSY": _glossy,
    "BSDF_ANISOTROPIC": _glossy,
    "BSDF_METALLIC": _metallic,
    "BSDF_GLASS": _glass,
    "BSDF_REFRACTION": _refraction,
    "BSDF_TRANSPARENT": _transparent,
    "BSDF_TRANSLUCENT": _translucent,
    "EMISSION": _emission,
    "HOLDOUT": _holdout,
}
