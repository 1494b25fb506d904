"""Blender's Boolean modifiers as exact CSG (`core.Csg`).

An object with Boolean modifiers (enabled for render) renders as its base shape (a tagged
primitive, or the object's own mesh before modifiers) combined with each modifier's operand
in modifier order: an object operand, or a collection operand (the union of its objects).
An operand with Boolean modifiers of its own nests. Operands are placed relative to the
object that uses them, from both objects' world matrices, and are used whether or not they
are hidden from render (Blender users hide their cutters). The viewport shows Blender's
mesh approximation; the render is exact.
"""

from __future__ import annotations

import numpy as np

from .. import core
from ..core.vocabulary import CSG_OPERATIONS

# Blender's Boolean operations onto core's (core.vocabulary, which lists them)
OPERATIONS = {"UNION": "union", "INTERSECT": "intersection", "DIFFERENCE": "difference"}
assert set(OPERATIONS.values()) == set(CSG_OPERATIONS)
SOLID_TYPES = {"MESH"}


def boolean_modifiers(obj) -> list:
    return [m for m in obj.modifiers if m.type == "BOOLEAN" and m.show_render]


def operand_objects(modifier) -> list:
    if modifier.operand_type == "COLLECTION":
        if modifier.collection is None:
            return []
        return [o for o in modifier.collection.all_objects if o.type in SOLID_TYPES]
    return [] if modifier.object is None else [modifier.object]


def world_matrix(obj, depsgraph) -> np.ndarray:
    """The object's evaluated world matrix (drivers, constraints and parents applied)."""
    try:
        return np.array(obj.evaluated_get(depsgraph).matrix_world, float)
    except (RuntimeError, ReferenceError):
        return np.array(obj.matrix_world, float)


def convert(obj, exporter, depsgraph, path=()) -> core.Shape:
    """`obj` (an original, not evaluated, object) as a core shape in its own object space:
    its base shape, then each Boolean modifier applied in order."""
    path = (*path, obj.name)
    node = exporter.base_shape(obj)
    here = world_matrix(obj, depsgraph)
    to_here = np.linalg.inv(here) if abs(np.linalg.det(here[:3, :3])) > 0.0 else None
    for modifier in boolean_modifiers(obj):
        operands = []
        for operand in operand_objects(modifier):
            if operand.name in path:
                chain = " -> ".join(f"'{name}'" for name in (*path, operand.name))
                raise core.SceneError(
                    f"object '{obj.name}'",
                    f"modifier '{modifier.name}'",
                    f"its operand uses the object itself ({chain}); Boolean operands "
                    "cannot form a cycle",
                )
            if to_here is None:
                raise core.SceneError(
                    f"object '{obj.name}'",
                    "scale",
                    "is zero on some axis; an object with Boolean modifiers needs an "
                    "invertible transform",
                )
            shape = convert(operand, exporter, depsgraph, path)
            shape.world_from_object = to_here @ world_matrix(operand, depsgraph)
            operands.append(shape)
        if not operands:
            exporter.warn(
                f"object '{obj.name}': Boolean modifier '{modifier.name}' has no operand "
                "object; it is ignored"
            )
            continue
        right = operands[0]
        for more in operands[1:]:
            right = core.Csg(f"{modifier.name} operands", operation="union", left=right,
                             right=more)  # fmt: skip
        node = core.Csg(
            f"{obj.name}: {modifier.name}",
            operation=OPERATIONS[modifier.operation],
            left=node,
            right=right,
        )
    return node
