"""Emissive surfaces lighting the scene (core.compile.glowing) against closed forms, on the
white plane of tests/core/test_emitters.py (each pixel shows E / pi):

- an emissive mesh quad of radiance L: Lambert's polygon formula for its irradiance, whatever
  the quad's tilt, triangles and the side it is seen from (both sides emit)
- an emissive ball of radius r and radiance L above the plane: E = pi L cos (r / d)^2 where
  the whole ball is above the horizon
- a quad whose emission is a checker lights as the sum of Lambert's formula over its cells,
  each of its own colour (core.kernels.glow_bake: the cells' edges fall on the sub-triangles'
  edges, so the bake is exact and only the samples' noise is left)
- switched off (Material.emission_lights, Shape.lights_diffuse) it lights nothing, and a
  shape other than a mesh whose emission varies over it says that it lights nothing"""

import math

import numpy as np
import pytest

from core import Material, Mesh, ShaderNode, Sphere, TriangleMesh
from core.compile import compile_scene
from tests.core.test_emitters import (
    assert_converged,
    pixel_points,
    point_irradiance,
    polygon_irradiance,
    rendered,
)

L = 3.0  # the surfaces' radiance


def _glow(**fields):
    return Material(diffuse=(0.0, 0.0, 0.0), emission=(L, L, L), **fields)


def _quad(corners, material=None, flip=False):
    triangles = np.array([[0, 1, 2], [0, 2, 3]])
    if flip:
        triangles = triangles[:, ::-1]
    mesh = TriangleMesh(np.asarray(corners, float), triangles)
    return Mesh("Lamp", material or _glow(), mesh=mesh, seen_by_camera=False)


# A tilted quad, flat (a bent one shades itself where the polygon formula does not)
_XY = np.array([[-0.8, -0.5], [0.9, -0.6], [1.0, 0.7], [-0.7, 0.6]])
CORNERS = np.column_stack([_XY, 1.6 + 0.2 * _XY[:, 0] + 0.25 * _XY[:, 1]])


def _expected(corners):
    return np.array([[polygon_irradiance(list(corners), p, L) for p in r] for r in pixel_points()])


def test_an_emissive_mesh_lights_as_lamberts_polygon_formula_from_either_side():
    expected = _expected(CORNERS)
    for flip in (False, True):
        # picking a triangle, then a point on it, stratifies less well than a panel's square
        got = rendered([], 4096, shapes=[_quad(CORNERS, flip=flip)])
        assert_converged(got, expected, rtol=6e-3)


def test_an_emissive_ball_lights_as_a_sphere_of_its_radiance():
    radius, centre = 0.6, (0.4, -0.3, 2.4)
    m = np.diag([radius, radius, radius, 1.0])
    m[:3, 3] = centre
    ball = Sphere("Glow", _glow(), m, seen_by_camera=False)
    # pi L r^2 cos / d^2: a sphere's irradiance is its centre's, with intensity L pi r^2
    expected = point_irradiance(centre, L * math.pi * radius**2)
    assert_converged(rendered([], 1024, shapes=[ball]), expected)


def test_switched_off_an_emissive_surface_lights_nothing():
    off = _quad(CORNERS, _glow(emission_lights=False))
    assert np.all(rendered([], 16, shapes=[off]) == 0.0)
    unlit = _quad(CORNERS)
    unlit.lights_diffuse = False
    assert np.all(rendered([], 16, shapes=[unlit]) == 0.0)


def _checkered_warnings(closure: str, name: str) -> list:
    """The compile's warnings for a quad whose `closure` (Emission or Diffuse) takes its
    colour from a Checker."""
    from core import Camera, Link, RenderSettings, Scene

    surface = ShaderNode(closure, {"Color": Link(ShaderNode("checker"), "Color")})
    quad = _quad(CORNERS, Material(name=name, surface=surface))
    camera = Camera(eye=(0.0, 0.0, 10.0), view=(0.0, 0.0, -1.0), up=(0.0, 1.0, 0.0))
    return compile_scene(Scene(camera, [quad]), RenderSettings(4, 4)).warnings


CHECKER_COLOURS = ((4.0, 1.0, 0.5), (0.2, 0.5, 2.0))


def _checker_colour(x, y):
    """Blender's Checker at object point (x, y, 0), Scale 1: Color1 where the cells' x and y
    numbers differ in parity (z's cell is 0)."""
    first = (math.floor(x) % 2 == math.floor(y) % 2) == 0
    return np.array(CHECKER_COLOURS[0] if first else CHECKER_COLOURS[1])


def test_an_emission_checker_lights_as_the_sum_of_its_cells():
    from core import Link

    at = ShaderNode("tex_coord")
    first, second = CHECKER_COLOURS
    checker = ShaderNode("checker", {"Vector": Link(at, "Object"), "Scale": 1.0,
                                     "Color1": first, "Color2": second})  # fmt: skip
    surface = ShaderNode("emission", {"Color": Link(checker, "Color"), "Strength": 1.0})
    corners = np.array([[-1.0, -1.0, 0.0], [1.0, -1.0, 0.0], [1.0, 1.0, 0.0], [-1.0, 1.0, 0.0]])
    quad = _quad(corners, Material(name="Checker", surface=surface))
    quad.world_from_object = np.array(
        [[1.0, 0, 0, 0.3], [0, 1.0, 0, -0.2], [0, 0, 1.0, 1.4], [0, 0, 0, 1.0]]
    )
    expected = np.zeros((*pixel_points().shape[:2], 3))
    for x0, y0 in ((-1.0, -1.0), (0.0, -1.0), (0.0, 0.0), (-1.0, 0.0)):
        cell = [(x0 + dx + 0.3, y0 + dy - 0.2, 1.4) for dx, dy in ((0, 0), (1, 0), (1, 1), (0, 1))]
        colour = _checker_colour(x0 + 0.5, y0 + 0.5)
        unit = np.array([[polygon_irradiance(cell, p, 1.0) for p in r] for r in pixel_points()])
        expected += unit[..., None] * colour
    got = rendered([], 4096, shapes=[quad], channels=3)
    # the sub-triangles are picked by their mean over RGB: each channel's noise is larger
    # than a constant quad's (0.9% against 0.6% at most)
    assert_converged(got, expected, rtol=1e-2)
    # each cell's colour shows: red under the warm cells, blue under the cool ones
    assert got[3, 3, 0] > 1.5 * got[3, 3, 2] or got[3, 3, 2] > 1.5 * got[3, 3, 0]


def test_an_emission_that_varies_over_a_ball_says_it_lights_nothing():
    from core import Camera, Link, RenderSettings, Scene

    surface = ShaderNode("emission", {"Color": Link(ShaderNode("checker"), "Color")})
    ball = Sphere("Lamp", Material(name="Patchy", surface=surface), seen_by_camera=False)
    camera = Camera(eye=(0.0, 0.0, 10.0), view=(0.0, 0.0, -1.0), up=(0.0, 1.0, 0.0))
    warnings = compile_scene(Scene(camera, [ball]), RenderSettings(4, 4)).warnings
    assert any("'Lamp'" in w and "varies" in w for w in warnings), warnings
    assert _checkered_warnings("emission", "Patchy") == []  # a mesh: it lights


def test_a_textured_surface_that_emits_nothing_says_nothing_of_glowing():
    assert _checkered_warnings("diffuse", "Tiles") == []


def test_past_the_cap_only_the_brightest_emissive_surfaces_light_and_it_is_said():
    from core import Camera, RenderSettings, Scene
    from core.compile.glowing import MAX_GLOWING

    dim = [_quad(CORNERS + (0.0, 0.0, k), _glow()) for k in range(MAX_GLOWING)]
    bright = _quad(CORNERS + (0.0, 0.0, 9.0), Material(diffuse=(0, 0, 0), emission=(50.0,) * 3))
    camera = Camera(eye=(0.0, 0.0, 20.0), view=(0.0, 0.0, -1.0), up=(0.0, 1.0, 0.0))
    compiled = compile_scene(Scene(camera, [*dim, bright]), RenderSettings(4, 4))
    lights = compiled.packed.lights
    assert len(lights.emitter_kind) == MAX_GLOWING
    assert lights.emitter_radiance.max() == pytest.approx(50.0 / np.pi)  # the bright one kept
    assert any(f"{MAX_GLOWING + 1} emissive objects" in w for w in compiled.warnings)
