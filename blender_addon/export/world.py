"""The world -> one colour: its Background node colour times strength, which is both the
ambient term and the background."""

from __future__ import annotations

from .material import find_node


def convert(world) -> tuple[float, float, float]:
    if world is None:
        return (0.0, 0.0, 0.0)
    background = find_node(world, "BACKGROUND")
    if background is not None:
        colour, strength = background.inputs[0].default_value, background.inputs[1].default_value
        return tuple(float(c) * strength for c in colour[:3])
    return tuple(float(c) for c in world.color)
