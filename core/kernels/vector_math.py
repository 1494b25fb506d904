"""Blender's Vector Math node, as Cycles computes it (safe division and normalisation: a zero
divisor or vector gives zero, not a NaN). Each operation gives a vector or a value; the other
output is zero."""

import math

from ..jit.decorators import kernel
from .shader_values import (
    M_ABSOLUTE,
    M_CEIL,
    M_COSINE,
    M_DIVIDE,
    M_FLOOR,
    M_FRACT,
    M_MAXIMUM,
    M_MINIMUM,
    M_MODULO,
    M_MULTIPLY,
    M_MULTIPLY_ADD,
    M_POWER,
    M_SIGN,
    M_SINE,
    M_SNAP,
    M_TANGENT,
    M_WRAP,
    math_node,
)
from .vec import add, cross, dot, scale, sub

# Operations (core.model.shader.VECTOR_MATH_OPERATIONS, in that order)
(V_ADD, V_SUBTRACT, V_MULTIPLY, V_DIVIDE, V_MULTIPLY_ADD, V_CROSS, V_PROJECT, V_REFLECT,
 V_REFRACT, V_FACEFORWARD, V_DOT, V_DISTANCE, V_LENGTH, V_SCALE, V_NORMALIZE, V_ABSOLUTE,
 V_POWER, V_SIGN, V_MINIMUM, V_MAXIMUM, V_FLOOR, V_CEIL, V_FRACTION, V_MODULO, V_WRAP, V_SNAP,
 V_SINE, V_COSINE, V_TANGENT) = range(29)  # fmt: skip

ZERO = (0.0, 0.0, 0.0)


@kernel
def _safe_normalize(a):
    length = math.sqrt(dot(a, a))
    return scale(a, 1.0 / length) if length != 0.0 else ZERO


# The Math node's operation each per-component Vector Math operation is (its safe variants
# are Cycles' for vectors too), -1 for the others
PER_COMPONENT = (
    -1, -1, M_MULTIPLY, M_DIVIDE, M_MULTIPLY_ADD, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1,
    M_ABSOLUTE, M_POWER, M_SIGN, M_MINIMUM, M_MAXIMUM, M_FLOOR, M_CEIL, M_FRACT, M_MODULO,
    M_WRAP, M_SNAP, M_SINE, M_COSINE, M_TANGENT,
)  # fmt: skip


@kernel
def vector_math(op, a, b, c, factor):
    """(vector, value) of operation `op` on the vectors a, b, c and the number `factor`
    (the node's Scale: the scale of Scale, the IOR of Refract)."""
    if op == V_ADD:
        return add(a, b), 0.0
    if op == V_SUBTRACT:
        return sub(a, b), 0.0
    if op == V_CROSS:
        return cross(a, b), 0.0
    if op == V_PROJECT:
        length2 = dot(b, b)
        return (scale(b, dot(a, b) / length2) if length2 != 0.0 else ZERO), 0.0
    if op == V_REFLECT:
        n = _safe_normalize(b)
        return sub(a, scale(n, 2.0 * dot(n, a))), 0.0
    if op == V_REFRACT:
        n = _safe_normalize(b)
        cos = dot(n, a)
        k = 1.0 - factor * factor * (1.0 - cos * cos)
        if k < 0.0:
            return ZERO, 0.0
        return sub(scale(a, factor), scale(n, factor * cos + math.sqrt(k))), 0.0
    if op == V_FACEFORWARD:
        return (a if dot(c, b) < 0.0 else scale(a, -1.0)), 0.0
    if op == V_DOT:
        return ZERO, dot(a, b)
    if op == V_DISTANCE:
        d = sub(a, b)
        return ZERO, math.sqrt(dot(d, d))
    if op == V_LENGTH:
        return ZERO, math.sqrt(dot(a, a))
    if op == V_SCALE:
        return scale(a, factor), 0.0
    if op == V_NORMALIZE:
        return _safe_normalize(a), 0.0
    each = PER_COMPONENT[op]
    return (math_node(each, a[0], b[0], c[0]), math_node(each, a[1], b[1], c[1]),
            math_node(each, a[2], b[2], c[2])), 0.0  # fmt: skip
