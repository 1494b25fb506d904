"""RGB Curves' lookup (core.kernels.shader_values.rgb_curves) on tables whose curves are
known in closed form: straight lines are reproduced exactly, inside the table and, extended
along the end slope, beyond it; flat extension holds the end rows. Compared with Cycles in
tests/blender/test_cycles_value_nodes.py."""

import numpy as np
import pytest

from core.kernels.shader_values import rgb_curves
from core.model.shader import CURVE_TABLE_SIZE


def _stack(curve, low=0.0, high=1.0, extrapolate=True):
    x = np.linspace(low, high, CURVE_TABLE_SIZE)
    table = np.stack([curve(x), 2.0 * curve(x), np.full_like(x, 0.25)], axis=1)
    return np.concatenate([[low, high, float(extrapolate)], table.ravel()])


@pytest.mark.parametrize("x", [-0.5, 0.0, 0.123, 0.5, 0.999, 1.0, 1.7])
def test_a_straight_curve_is_reproduced_and_extended_along_its_slope(x):
    stack = _stack(lambda x: 0.3 + 0.5 * x, low=-0.2, high=1.2)
    r, g, b = rgb_curves(stack, 0, CURVE_TABLE_SIZE, (x, x, x))
    assert r == pytest.approx(0.3 + 0.5 * x, abs=1e-12)
    assert g == pytest.approx(2.0 * (0.3 + 0.5 * x), abs=1e-12)
    assert b == pytest.approx(0.25, abs=1e-12)


def test_a_curve_between_rows_is_linear_and_held_flat_when_not_extrapolated():
    stack = _stack(lambda x: x * x, extrapolate=False)
    step = 1.0 / (CURVE_TABLE_SIZE - 1)
    x = 10.5 * step  # halfway between rows 10 and 11
    r, _, _ = rgb_curves(stack, 0, CURVE_TABLE_SIZE, (x, x, x))
    assert r == pytest.approx(0.5 * ((10 * step) ** 2 + (11 * step) ** 2), abs=1e-12)
    assert rgb_curves(stack, 0, CURVE_TABLE_SIZE, (1.8, -0.4, 0.0))[:2] == (1.0, 0.0)


@pytest.mark.parametrize(
    "node, message",
    [
        (("rgb_curves", {}), r"node 'Curves' table: give 256 RGB rows"),
        (("rgb_curves", {"table": np.zeros((256, 3)), "range": (1.0, 1.0)}), r"range: give"),
        (("magic", {"depth": 12}), r"depth: got 12; use a whole number from 0 to 10"),
    ],
)
def test_a_value_node_with_bad_settings_is_refused_by_name(node, message):
    from core import Camera, Link, Material, RenderSettings, Scene, SceneError, ShaderNode, Sphere
    from core.compile import compile_scene

    kind, settings = node
    made = ShaderNode(kind, settings=settings, name="Curves")
    material = Material(name="Odd", surface=ShaderNode("emission", {"Color": Link(made, "Color")}))
    scene = Scene(Camera(), [Sphere("Ball", material, np.eye(4))])
    with pytest.raises(SceneError, match=r"material 'Odd'.*" + message):
        compile_scene(scene, RenderSettings(4, 4))
