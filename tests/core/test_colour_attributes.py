"""Colour attributes (Blender's Color Attribute and Attribute nodes; core.kernels.attributes)
against what the test computes itself: a square of two triangles, seen orthographically
face on, glowing with an attribute's output as its Emission colour, shows at each pixel
centre the corners' RGBA blended by that point's barycentric weights in its triangle
(worked out here from the pixel's position). A mesh that lacks the attribute reads 0, with
a warning naming the mesh, the attribute and the material; a malformed one is refused by
name. Side by side with Cycles, through Blender's own colour attributes:
tests/blender/test_cycles_colour_attributes.py."""

import numpy as np
import pytest

from core import (
    Environment,
    Link,
    Material,
    Mesh,
    RenderSettings,
    Scene,
    SceneError,
    ShaderNode,
    TriangleMesh,
)
from core.compile import compile_scene
from core.driver import render
from tests.core.test_environment import hits, look_at_ball

SIZE = 16
SQUARE = np.array([(-1, 0, -1), (1, 0, -1), (1, 0, 1), (-1, 0, 1)], float)  # faces -Y
TRIANGLES = np.array([(0, 1, 2), (0, 2, 3)])
RNG = np.random.default_rng(61)
PAINT = RNG.uniform(0.0, 1.0, (2, 3, 4)).astype(np.float32)  # per triangle corner, RGBA
DIRT = RNG.uniform(0.0, 1.0, (2, 3, 4)).astype(np.float32)


def _square(material, colors=None, default=""):
    mesh = TriangleMesh(SQUARE, TRIANGLES, corner_colors=colors, default_color=default,
                        name="Square")  # fmt: skip
    return Mesh("Square", material, np.eye(4), mesh=mesh)


def _glowing(name="", output="Color"):
    attribute = ShaderNode("attribute", {}, settings={"name": name})
    value = Link(attribute, output)
    return Material(surface=ShaderNode("emission", {"Color": value, "Strength": 1.0}))


def _seen(shape):
    scene = Scene(look_at_ball(), [shape], environment=Environment(colour=(0.0, 0.0, 0.0)))
    return render(scene, RenderSettings(SIZE, SIZE, pixel_samples=1)).image[..., :3]


def _expected(corners):
    """Each pixel centre's blend of its triangle's corner values (RGBA); NaN on the edge
    the two triangles share (the diagonal x = z), where either may be the one met."""
    points, _ = hits(SIZE)
    x, z = points[..., 0], points[..., 2]
    out = np.zeros((SIZE, SIZE, 4))
    for t, (a, b, c) in enumerate(TRIANGLES):
        p0, p1, p2 = SQUARE[a][[0, 2]], SQUARE[b][[0, 2]], SQUARE[c][[0, 2]]
        det = (p1[0] - p0[0]) * (p2[1] - p0[1]) - (p2[0] - p0[0]) * (p1[1] - p0[1])
        w1 = ((x - p0[0]) * (p2[1] - p0[1]) - (p2[0] - p0[0]) * (z - p0[1])) / det
        w2 = ((p1[0] - p0[0]) * (z - p0[1]) - (x - p0[0]) * (p1[1] - p0[1])) / det
        w0 = 1.0 - w1 - w2
        inside = (w0 >= 0) & (w1 >= 0) & (w2 >= 0)
        blend = w0[..., None] * corners[t, 0] + w1[..., None] * corners[t, 1]
        blend += w2[..., None] * corners[t, 2]
        out[inside] = blend[inside]
    out[np.isclose(x, z)] = np.nan
    return out


@pytest.mark.parametrize("name, default", [("Paint", ""), ("", "Paint"), ("Dirt", "Paint")])
def test_an_attribute_is_its_corners_blended_by_the_barycentric_weights(name, default):
    colors = {"Paint": PAINT, "Dirt": DIRT}
    seen = _seen(_square(_glowing(name), colors, default))
    wanted = _expected(DIRT if name == "Dirt" else PAINT)[..., :3]
    off_edge = np.isfinite(wanted)
    assert off_edge.mean() > 0.9
    np.testing.assert_allclose(seen[off_edge], wanted[off_edge], atol=2e-6)


@pytest.mark.parametrize("output", ["Alpha", "Fac"])
def test_its_alpha_and_fac_are_the_blended_alpha_and_the_mean_of_rgb(output):
    seen = _seen(_square(_glowing("Paint", output), {"Paint": PAINT}))
    blended = _expected(PAINT)
    wanted = blended[..., 3] if output == "Alpha" else blended[..., :3].mean(axis=-1)
    wanted = np.repeat(wanted[..., None], 3, -1)
    off_edge = np.isfinite(wanted)
    np.testing.assert_allclose(seen[off_edge], wanted[off_edge], atol=2e-6)


def test_a_mesh_without_the_attribute_reads_zero_and_is_named_in_a_warning():
    shape = _square(_glowing("Paint"), {"Dirt": DIRT})
    assert np.all(_seen(shape) == 0.0)
    scene = Scene(look_at_ball(), [shape])
    warnings = compile_scene(scene, RenderSettings(4, 4)).warnings
    assert any("'Square'" in w and "'Paint'" in w and "read as 0" in w for w in warnings)


@pytest.mark.parametrize(
    "colors, default, field",
    [
        ({"Paint": PAINT[:, :, :3]}, "", "corner_colors['Paint']"),
        ({"Paint": np.full((2, 3, 4), np.nan)}, "", "corner_colors['Paint']"),
        ({"Paint": PAINT}, "Dirt", "default_color"),
    ],
)
def test_malformed_attributes_are_refused_by_name(colors, default, field):
    scene = Scene(look_at_ball(), [_square(_glowing("Paint"), colors, default)])
    with pytest.raises(SceneError, match=field.replace("[", r"\[").replace("]", r"\]")):
        scene.validate()
