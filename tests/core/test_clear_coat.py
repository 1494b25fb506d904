"""The Principled BSDF's Coat (core.kernels.clear_coat) against closed forms computed here:
a ball seen orthographically (each pixel's cos = |I . N| known exactly) in a white World,
its base black with no specular layer, glowing under the coat. Each pixel is then

    F(cos) + max(0, 1 - c F(cos)) (1 + c (tint^(1 / cos_t) - 1)) E

F the exact dielectric reflectance of the coat's IOR (from Fresnel's amplitudes,
tests/core/test_node_material_terms._fresnel), c the Coat Weight, cos_t the cosine of the
view ray refracted into the coat, E the emission: the World the coat reflects, and the glow
the coat dims and tints, as Cycles layers them (its layering weight and Coat Tint). Side by
side with Cycles: tests/blender/test_cycles_clear_coat.py.

And the coat's terms fold into the material table when constant: the folded coat renders
the picture the per-hit program renders (an exact equivalence), and a scene without a coat
compiles no coat code (tests/core/test_kernel_variants.py checks the variant's pixels).
"""

import numpy as np
import pytest

from core import Environment, Link, Material, RenderSettings, Scene, ShaderNode, render
from core.compile.features import expected_features
from tests.core.test_environment import ball, hits, look_at_ball
from tests.core.test_node_material_terms import _fresnel

pytestmark = pytest.mark.filterwarnings("ignore:invalid value:RuntimeWarning")  # the rim's 0/0
SIZE = 24


def _coated(coat=1.0, ior=1.5, tint=(1.0, 1.0, 1.0), glow=0.0, roughness=0.0, **more):
    return ShaderNode("principled", {
        "Base Color": (0.0, 0.0, 0.0), "Specular": 0.0, "Roughness": 0.0,
        "Emission Color": (1.0, 1.0, 1.0), "Emission Strength": glow,
        "Coat Weight": coat, "Coat IOR": ior, "Coat Tint": tint, "Coat Roughness": roughness,
        **more,
    })  # fmt: skip


def _seen(surface):
    scene = Scene(look_at_ball(), [ball(Material(surface=surface))],
                  environment=Environment(colour=(1.0, 1.0, 1.0)))  # fmt: skip
    settings = RenderSettings(SIZE, SIZE, pixel_samples=1, max_depth=2, environment_samples=4)
    return render(scene, settings).image[..., :3].astype(float)


def _expected(cos, coat, ior, tint, glow):
    f = _fresnel(cos, 1.0, ior)
    cos_t = np.sqrt(1.0 - (1.0 - cos**2) / ior**2)
    tinted = 1.0 + coat * (np.asarray(tint)[None, :] ** (1.0 / cos_t[:, None]) - 1.0)
    under = np.clip(1.0 - coat * f, 0.0, None)[:, None] * tinted
    return coat * f[:, None] + under * glow


@pytest.mark.parametrize(
    "coat, ior, tint, glow",
    [
        (1.0, 1.5, (1.0, 1.0, 1.0), 0.0),  # the coat alone: the World in it, F
        (1.0, 1.5, (0.8, 0.5, 0.2), 1.0),  # the glow below, dimmed and tinted
        (0.6, 2.0, (0.3, 0.9, 0.6), 0.5),  # part of a coat, a denser one
    ],
)
def test_a_coat_reflects_its_fresnel_and_dims_and_tints_what_lies_below(coat, ior, tint, glow):
    seen = _seen(_coated(coat, ior, tint, glow))
    points, inside = hits(SIZE)
    cos = -points[..., 1][inside]
    np.testing.assert_allclose(seen[inside], _expected(cos, coat, ior, tint, glow), atol=2e-6)


def test_a_coat_mixed_by_a_texture_renders_as_the_folded_one():
    """The same coat, its weight once a constant (folded into the table) and once from a
    Math node of the texture coordinates that is constant 1 (run per hit): the same
    pixels."""
    folded = _seen(_coated(1.0, 1.6, (0.7, 0.6, 0.9), 0.5))
    coordinate = Link(ShaderNode("separate", {"Vector": Link(ShaderNode("tex_coord"), "UV")}), "X")
    one = ShaderNode("math", {"A": coordinate, "B": 0.0}, settings={"operation": "MULTIPLY"})
    plus = ShaderNode("math", {"A": Link(one, "Value"), "B": 1.0}, settings={"operation": "ADD"})
    per_hit = _seen(_coated(Link(plus, "Value"), 1.6, (0.7, 0.6, 0.9), 0.5))
    np.testing.assert_array_equal(folded, per_hit)


def test_only_a_coated_scene_compiles_the_coat():
    settings = RenderSettings(8, 8)
    for surface, wanted in ((_coated(0.0), False), (_coated(0.5), True)):
        scene = Scene(look_at_ball(), [ball(Material(surface=surface))])
        assert ("clear_coat" in expected_features(scene, settings)) == wanted
