"""The Wireframe node (core.kernels.attributes' edge distances, OP_WIREFRAME) against the
closed form worked out here: a square of two triangles, stretched unevenly by its object
transform, seen face on, glowing with the node's Fac. A pixel is wire when its centre lies
within Size / 2, in world units, of the line of an edge of the triangle it sees: the
square's four sides and the diagonal the two triangles share. Measured in object space,
the diagonal's band would come out at the wrong width. Side by side with Cycles:
tests/blender/test_cycles_textures.py."""

import numpy as np
import pytest

from core import (
    Environment,
    Link,
    Material,
    Mesh,
    RenderSettings,
    Scene,
    ShaderNode,
    Sphere,
    TriangleMesh,
)
from core.compile import compile_scene
from core.driver import render
from tests.core.test_environment import look_at_ball

SIZE = 16
# x 4 and z 8 across in object space; the transform halves x and quarters z: the 2 x 2 view
OBJECT_SQUARE = np.array([(-2, 0, -4), (2, 0, -4), (2, 0, 4), (-2, 0, 4)], float)
WORLD_FROM_OBJECT = np.diag((0.5, 1.0, 0.25, 1.0))
TRIANGLES = np.array([(0, 1, 2), (0, 2, 3)])


def _wire(size):
    fac = Link(ShaderNode("wireframe", {"Size": size}), "Fac")
    return Material(name="Wire", surface=ShaderNode("emission", {"Color": (1.0, 1.0, 1.0),
                                                                 "Strength": fac}))  # fmt: skip


def _scene(shape):
    return Scene(look_at_ball(), [shape], environment=Environment(colour=(0.0, 0.0, 0.0)))


def _square(material):
    mesh = TriangleMesh(OBJECT_SQUARE, TRIANGLES, name="Square")
    return Mesh("Square", material, WORLD_FROM_OBJECT, mesh=mesh)


def _expected(size):
    """1 where a pixel centre (world x, z) lies within size / 2 of the square's sides
    (x, z = +-1) or of its diagonal x = z."""
    c = ((np.arange(SIZE) + 0.5) / SIZE - 0.5) * 2.0
    x, z = np.meshgrid(c, -c)
    nearest = np.minimum.reduce([1 - np.abs(x), 1 - np.abs(z), np.abs(x - z) / np.sqrt(2)])
    return (nearest < abs(size) / 2).astype(float)


@pytest.mark.parametrize("size", [0.3, 0.6, -0.3])
def test_a_pixel_is_wire_within_half_the_size_of_an_edge_in_world_units(size):
    image = render(_scene(_square(_wire(size))), RenderSettings(SIZE, SIZE, pixel_samples=1))
    seen = image.image[..., 0].astype(float)
    wanted = _expected(size)
    assert 0.1 < wanted.mean() < 0.9
    np.testing.assert_array_equal(seen, wanted)


def test_an_exact_shape_has_no_edges_and_says_so():
    scene = _scene(Sphere("Ball", _wire(0.3), np.eye(4)))
    warnings = compile_scene(scene, RenderSettings(4, 4)).warnings
    assert any("sphere 'Ball'" in w and "Wireframe" in w and "Fac 0" in w for w in warnings)
    seen = render(scene, RenderSettings(SIZE, SIZE, pixel_samples=1)).image[..., :3]
    assert float(np.abs(seen).max()) == 0.0
