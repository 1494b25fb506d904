"""The Translucent BSDF (core.kernels.translucent) against closed forms computed here: a
square seen face on, lit from behind. A translucent colour k passes on k/pi of the light
falling on its back, so each pixel is

- under a sun behind it at angle theta to its normal: k E cos(theta) / pi, E the sun's
  irradiance; 0 where something behind it shadows its back;
- in a uniform World of radiance L (its back hemisphere's irradiance pi L): k L, with a
  diffuse colour kd beside it (its front hemisphere's): (kd + k) L.

And the translucency folded into the material table renders as the per-hit program does."""

import math

import numpy as np
import pytest

from core import (
    Box,
    Environment,
    Link,
    Material,
    Mesh,
    RenderSettings,
    Scene,
    ShaderNode,
    SunLight,
    TriangleMesh,
    render,
)
from core.compile import compile_scene
from core.compile.features import expected_features, used_features
from tests.core.test_colour_attributes import SQUARE, TRIANGLES
from tests.core.test_environment import hits, look_at_ball

SIZE = 16
PAPER = (0.7, 0.5, 0.2)  # the translucent colour k


def _square(material):
    """The square x, z in -1..1 at y = 0, facing the camera at -Y (it fills the picture)."""
    return Mesh("Paper", material, np.eye(4), mesh=TriangleMesh(SQUARE, TRIANGLES, name="Paper"))


def _translucent(colour=PAPER, diffuse=None):
    node = ShaderNode("translucent", {"Color": colour})
    if diffuse is None:
        return Material(surface=node)
    lambert = ShaderNode("diffuse", {"Color": diffuse})
    both = ShaderNode("add_shader", {"Shader A": Link(node), "Shader B": Link(lambert)})
    return Material(surface=both)


def _seen(shapes, lights=(), world=None, samples=4):
    scene = Scene(look_at_ball(), shapes, lights=list(lights), environment=world)
    settings = RenderSettings(SIZE, SIZE, pixel_samples=1, environment_samples=samples)
    return render(scene, settings).image[..., :3].astype(float)


def test_a_sun_behind_the_square_shines_through_it_by_k_cos_over_pi():
    behind = (0.3, -1.0, 0.2)  # travelling towards the camera: it lights the square's back
    sun = SunLight(name="Sun", direction=behind, irradiance=(2.0, 2.0, 2.0))
    seen = _seen([_square(_translucent())], [sun])
    cos = 1.0 / np.linalg.norm(behind)
    expected = np.asarray(PAPER) * 2.0 * cos / math.pi
    np.testing.assert_allclose(seen.reshape(-1, 3), np.tile(expected, (SIZE * SIZE, 1)),
                               rtol=1e-6)  # fmt: skip


def test_the_sun_on_its_front_does_not_shine_through():
    sun = SunLight(name="Sun", direction=(0.0, 1.0, 0.0), irradiance=(2.0, 2.0, 2.0))
    assert _seen([_square(_translucent())], [sun]).max() == 0.0


def test_what_shadows_its_back_darkens_it():
    """A block behind the square's x > 0 half, between it and the sun."""
    sun = SunLight(name="Sun", direction=(0.0, -1.0, 0.0), irradiance=(1.0, 1.0, 1.0))
    block = np.diag([1.0, 0.2, 2.0, 1.0])
    block[:3, 3] = (1.0, 1.0, 0.0)  # x 0..2, y 0.8..1.2
    shapes = [_square(_translucent()), Box("Block", Material(), block)]
    seen = _seen(shapes, [sun])
    points, _ = hits(SIZE)
    lit = points[..., 0] < 0.0
    np.testing.assert_allclose(seen[lit], np.tile(np.asarray(PAPER) / math.pi, (lit.sum(), 1)),
                               rtol=1e-6)  # fmt: skip
    assert seen[~lit].max() == 0.0


def test_a_uniform_world_gives_k_plus_kd_times_its_radiance():
    world = Environment(colour=(0.6, 0.8, 1.0))
    seen = _seen([_square(_translucent(diffuse=(0.1, 0.2, 0.3)))], world=world)
    expected = (np.asarray(PAPER) + (0.1, 0.2, 0.3)) * (0.6, 0.8, 1.0)
    np.testing.assert_allclose(seen.reshape(-1, 3), np.tile(expected, (SIZE * SIZE, 1)),
                               rtol=1e-5)  # fmt: skip


def test_a_folded_translucency_renders_as_the_per_hit_one():
    """The same colour once a constant (folded into the table) and once through a Math
    node of the texture coordinates that is constant (run per hit)."""
    sun = SunLight(name="Sun", direction=(0.2, -1.0, -0.1), irradiance=(1.5, 1.5, 1.5))
    folded = _seen([_square(_translucent())], [sun])
    coordinate = Link(ShaderNode("separate", {"Vector": Link(ShaderNode("tex_coord"), "UV")}), "X")
    zero = ShaderNode("math", {"A": coordinate, "B": 0.0}, settings={"operation": "MULTIPLY"})
    fac = Link(ShaderNode("math", {"A": Link(zero, "Value"), "B": 1.0},
                          settings={"operation": "ADD"}), "Value")  # fmt: skip
    paper = ShaderNode("translucent", {"Color": PAPER})
    mixed = ShaderNode("mix_shader", {"Fac": fac, "Shader A": Link(ShaderNode("diffuse")),
                                      "Shader B": Link(paper)})  # fmt: skip
    per_hit = _seen([_square(Material(surface=mixed))], [sun])
    np.testing.assert_array_equal(folded, per_hit)
    assert folded.max() > 0.1


@pytest.mark.parametrize("translucent", [True, False])
def test_the_translucent_feature_is_compiled_only_where_used(translucent):
    material = _translucent() if translucent else Material(surface=ShaderNode("diffuse"))
    scene = Scene(look_at_ball(), [_square(material)])
    settings = RenderSettings(8, 8)
    assert ("translucent" in used_features(compile_scene(scene, settings).packed)) == translucent
    assert ("translucent" in expected_features(scene, settings)) == translucent
