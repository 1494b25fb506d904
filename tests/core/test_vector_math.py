"""The Vector Math node (core.kernels.vector_math) against numpy's own vector algebra, and the
Mix Color blends added for issue 61 against the properties that define them. Both are also
compared with Cycles pixel by pixel in tests/blender/test_cycles_value_nodes.py."""

import math

import numpy as np
import pytest

from core.kernels.shader_values import (
    B_BURN,
    B_COLOR,
    B_DODGE,
    B_HUE,
    B_LINEAR_LIGHT,
    B_SATURATION,
    B_SOFT_LIGHT,
    B_VALUE,
    _rgb_to_hsv,
    mix_colour,
)
from core.kernels.vector_math import vector_math
from core.model.shader import VECTOR_MATH_OPERATIONS


def _unit(v):
    n = np.linalg.norm(v)
    return v / n if n else np.zeros(3)


def _reference(op, a, b, c, s):
    """(vector, value) from numpy, written from Blender's manual."""
    zero = np.zeros(3)
    with np.errstate(divide="ignore", invalid="ignore"):
        safe = np.where(b != 0.0, a / np.where(b != 0.0, b, 1.0), 0.0)
    n = _unit(b)
    k = 1.0 - s * s * (1.0 - np.dot(n, a) ** 2)
    table = {
        "ADD": a + b, "SUBTRACT": a - b, "MULTIPLY": a * b, "DIVIDE": safe,
        "MULTIPLY_ADD": a * b + c, "CROSS_PRODUCT": np.cross(a, b),
        "PROJECT": b * np.dot(a, b) / np.dot(b, b) if np.dot(b, b) else zero,
        "REFLECT": a - 2.0 * np.dot(n, a) * n,
        "REFRACT": s * a - (s * np.dot(n, a) + math.sqrt(k)) * n if k >= 0 else zero,
        "FACEFORWARD": a if np.dot(c, b) < 0 else -a, "SCALE": a * s, "NORMALIZE": _unit(a),
        "ABSOLUTE": np.abs(a), "SIGN": np.sign(a), "MINIMUM": np.minimum(a, b),
        "MAXIMUM": np.maximum(a, b), "FLOOR": np.floor(a), "CEIL": np.ceil(a),
        "FRACTION": a - np.floor(a), "MODULO": np.where(b != 0, np.fmod(a, np.where(b, b, 1)), 0),
        "WRAP": np.where(b != c, a - (b - c) * np.floor((a - c) / np.where(b != c, b - c, 1)), c),
        "SNAP": np.floor(safe) * b, "SINE": np.sin(a), "COSINE": np.cos(a), "TANGENT": np.tan(a),
    }  # fmt: skip
    values = {"DOT_PRODUCT": np.dot(a, b), "DISTANCE": np.linalg.norm(a - b),
              "LENGTH": np.linalg.norm(a)}  # fmt: skip
    if op == "POWER":
        power = [x**y if x > 0 or (x < 0 and y == int(y)) else (0.0 if x or y > 0 else 1.0)
                 for x, y in zip(a, b, strict=True)]  # fmt: skip
        return np.array(power), 0.0
    if op in values:
        return zero, values[op]
    return table[op], 0.0


@pytest.mark.parametrize("op", VECTOR_MATH_OPERATIONS)
def test_each_vector_math_operation_is_blenders(op):
    code = VECTOR_MATH_OPERATIONS.index(op)
    rng = np.random.default_rng(61)
    cases = [rng.uniform(-2.0, 2.0, (3, 3)) for _ in range(20)]
    cases.append(np.array([[0.5, -1.0, 2.0], [0.0, 0.0, 0.0], [1.0, 1.0, 1.0]]))  # zero B
    cases.append(np.array([[1.0, 2.0, -3.0], [2.0, -1.0, 0.0], [0.0, 0.0, 0.0]]))  # int powers
    for a, b, c in cases:
        for scale in (0.75, 1.6):
            vector, value = vector_math(code, tuple(a), tuple(b), tuple(c), scale)
            expected_vector, expected_value = _reference(op, a, b, c, scale)
            np.testing.assert_allclose(vector, expected_vector, rtol=1e-12, atol=1e-12)
            assert value == pytest.approx(expected_value, abs=1e-12)


A, B = (0.3, 0.6, 0.9), (0.8, 0.2, 0.4)


def test_the_hsv_blends_take_hue_saturation_and_value_from_b():
    full = {k: mix_colour(k, 1.0, A, B) for k in (B_HUE, B_SATURATION, B_VALUE, B_COLOR)}
    ha, sa, va = _rgb_to_hsv(A)
    hb, sb, vb = _rgb_to_hsv(B)
    np.testing.assert_allclose(_rgb_to_hsv(full[B_HUE]), (hb, sa, va), atol=1e-12)
    np.testing.assert_allclose(_rgb_to_hsv(full[B_SATURATION]), (ha, sb, va), atol=1e-12)
    np.testing.assert_allclose(_rgb_to_hsv(full[B_VALUE]), (ha, sa, vb), atol=1e-12)
    np.testing.assert_allclose(_rgb_to_hsv(full[B_COLOR]), (hb, sb, va), atol=1e-12)
    grey = (0.5, 0.5, 0.5)  # a grey B has no hue to give
    assert mix_colour(B_HUE, 1.0, A, grey) == A and mix_colour(B_COLOR, 1.0, A, grey) == A


@pytest.mark.parametrize("blend", [B_BURN, B_DODGE, B_HUE, B_SATURATION, B_VALUE, B_COLOR,
                                   B_SOFT_LIGHT, B_LINEAR_LIGHT])  # fmt: skip
def test_a_blend_at_factor_zero_is_its_first_colour(blend):
    np.testing.assert_allclose(mix_colour(blend, 0.0, A, B), A, atol=1e-12)


def test_burn_dodge_soft_and_linear_light_follow_their_formulas():
    for a, b in zip(A, B, strict=True):
        index = A.index(a)
        assert mix_colour(B_BURN, 1.0, A, B)[index] == pytest.approx(max(0.0, 1 - (1 - a) / b))
        assert mix_colour(B_DODGE, 1.0, A, B)[index] == pytest.approx(min(1.0, a / (1 - b)))
        screen = 1 - (1 - b) * (1 - a)
        soft = (1 - a) * b * a + a * screen
        assert mix_colour(B_SOFT_LIGHT, 1.0, A, B)[index] == pytest.approx(soft)
        assert mix_colour(B_LINEAR_LIGHT, 0.5, A, B)[index] == pytest.approx(a + 0.5 * (2 * b - 1))
