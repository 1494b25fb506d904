"""Tangent-space normal maps on a mesh's own tangents (TriangleMesh.corner_tangents, Blender's
MikkTSpace ones; core.kernels.shader_program._normal_map), against Cycles' rule computed
here: the colour c gives m = 2c - 1 in the frame of the tangent T (interpolated over the
triangle), the bitangent sign x N x T and the normal N, so a map of m = (1, 0, 0) turns the
normal to T itself and m = (0, 1, 0) to the bitangent. A square facing the camera glows
with the mapped normal, (n + 1) / 2."""

import numpy as np
import pytest

from core import Link, Material, Mesh, RenderSettings, Scene, ShaderNode, TriangleMesh, render
from tests.core.test_colour_attributes import SQUARE, TRIANGLES, _expected
from tests.core.test_environment import look_at_ball

SIZE = 16
RNG = np.random.default_rng(7)


def _glowing_normal(colour):
    mapped = ShaderNode("normal_map", {"Color": colour})
    shifted = ShaderNode("vector_math", {"A": Link(mapped, "Normal"), "B": (1.0, 1.0, 1.0)})
    half = ShaderNode("vector_math", {"A": Link(shifted, "Vector"), "Scale": 0.5},
                      settings={"operation": "SCALE"})  # fmt: skip
    return Material(surface=ShaderNode("emission", {"Color": Link(half, "Vector")}))


def _seen(colour, tangents):
    uvs = (SQUARE[:, [0, 2]] + 1.0) / 2.0  # u along +x, v along +z
    mesh = TriangleMesh(SQUARE, TRIANGLES, corner_tangents=tangents, vertex_uvs=uvs, name="Card")
    scene = Scene(look_at_ball(), [Mesh("Card", _glowing_normal(colour), np.eye(4), mesh=mesh)])
    return render(scene, RenderSettings(SIZE, SIZE, pixel_samples=1)).image[..., :3]


def _tangents(sign):
    """Random tangents across the square (y = 0: in its plane), per corner, and the sign."""
    xz = RNG.uniform(-1.0, 1.0, (2, 3, 2))
    tangents = np.zeros((2, 3, 4))
    tangents[..., 0], tangents[..., 2], tangents[..., 3] = xz[..., 0], xz[..., 1], sign
    return tangents


@pytest.mark.parametrize("sign", [1.0, -1.0])
def test_the_map_turns_the_normal_to_the_interpolated_tangent_and_bitangent(sign):
    tangents = _tangents(sign)
    blended = _expected(tangents)  # per pixel, the corners' barycentric blend (NaN: edge)
    off_edge = np.isfinite(blended[..., 0])
    t = blended[off_edge][:, :3]
    t /= np.linalg.norm(t, axis=1, keepdims=True)
    along_t = _seen((1.0, 0.5, 0.5), tangents)[off_edge]
    np.testing.assert_allclose(along_t, (t + 1.0) / 2.0, atol=1e-5)
    n = np.array([0.0, -1.0, 0.0])  # the square faces the camera at -Y
    b = sign * np.cross(n, t)
    along_b = _seen((0.5, 1.0, 0.5), tangents)[off_edge]
    np.testing.assert_allclose(along_b, (b + 1.0) / 2.0, atol=1e-5)


def test_without_tangents_the_triangles_uv_gradient_is_the_tangent():
    """The square's UVs run u along +x on both triangles: T = +x, unlike the given ones."""
    seen = _seen((1.0, 0.5, 0.5), None)
    np.testing.assert_allclose(seen.reshape(-1, 3).mean(axis=0), (1.0, 0.5, 0.5), atol=1e-5)
    assert not np.allclose(_seen((1.0, 0.5, 0.5), _tangents(1.0)), seen, atol=0.05)
