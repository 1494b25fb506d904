"""The Geometry node (core.kernels.shader_program.geometry_vector) against what each pixel's
hit is, known here: a unit ball seen orthographically from -Y (each pixel centre's point
and normal exact, tests.core.test_environment.hits) glowing with an output, mapped to
0..1 as (v + 1) / 2; and a square seen from behind, whose Backfacing is 1 and whose normals
face the camera, as Cycles turns them."""

import numpy as np
import pytest

from core import Link, Material, Mesh, RenderSettings, Scene, ShaderNode, TriangleMesh, render
from tests.core.test_colour_attributes import SQUARE, TRIANGLES
from tests.core.test_environment import ball, hits, look_at_ball

SIZE = 12
GEOMETRY = ShaderNode("geometry")


def _glowing(output, kind="triple"):
    """A material glowing with the Geometry output, (v + 1) / 2 of a vector."""
    if kind == "value":
        colour = Link(ShaderNode("combine", {"X": Link(GEOMETRY, output)}), "Vector")
    else:
        shifted = ShaderNode("vector_math", {"A": Link(GEOMETRY, output), "B": (1.0, 1.0, 1.0)})
        half = ShaderNode("vector_math", {"A": Link(shifted, "Vector"), "Scale": 0.5},
                          settings={"operation": "SCALE"})  # fmt: skip
        colour = Link(half, "Vector")
    return Material(surface=ShaderNode("emission", {"Color": colour, "Strength": 1.0}))


def _seen(shape):
    settings = RenderSettings(SIZE, SIZE, pixel_samples=1)
    return render(Scene(look_at_ball(), [shape]), settings).image[..., :3].astype(float)


@pytest.mark.parametrize("output", ["Position", "Normal", "True Normal"])
def test_a_balls_position_and_normals_are_its_points(output):
    """On the unit ball at the origin the point is its own normal (the exact sphere's
    geometric and shading normals agree)."""
    seen = _seen(ball(_glowing(output)))
    points, inside = hits(SIZE)
    np.testing.assert_allclose(seen[inside], (points[inside] + 1.0) / 2.0, atol=1e-6)


def test_incoming_points_back_along_the_ray():
    seen = _seen(ball(_glowing("Incoming")))
    _, inside = hits(SIZE)
    np.testing.assert_allclose(seen[inside], np.tile((0.5, 0.0, 0.5), (inside.sum(), 1)),
                               atol=1e-6)  # fmt: skip


@pytest.mark.parametrize("backfacing", [0.0, 1.0])
def test_a_square_seen_from_behind_is_backfacing_its_normals_turned_to_the_ray(backfacing):
    """SQUARE's triangles face -Y (the camera); wound the other way they face away."""
    triangles = TRIANGLES[:, ::-1] if backfacing else TRIANGLES
    mesh = TriangleMesh(SQUARE + (0.0, 0.5, 0.0), triangles)
    seen = _seen(Mesh("Card", _glowing("Backfacing", "value"), np.eye(4), mesh=mesh))
    np.testing.assert_allclose(seen[..., 0], backfacing, atol=1e-6)
    normal = _seen(Mesh("Card", _glowing("True Normal"), np.eye(4), mesh=mesh))
    np.testing.assert_allclose(normal.reshape(-1, 3), np.tile((0.5, 0.0, 0.5), (SIZE * SIZE, 1)),
                               atol=1e-6)  # fmt: skip
