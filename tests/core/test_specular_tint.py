"""The Principled BSDF's Specular Tint (Blender 4.0 on) against closed forms computed here: a
sharp ball with a black base in a white World, seen orthographically (each pixel's
cos = |I . N| known exactly), shows its specular layer's reflectance at each pixel:

- a dielectric: Cycles' tinted Fresnel, F0 t + (1 - F0 t) s with s = (F - F0) / (1 - F0) and F
  the exact dielectric reflectance (tests/core/test_node_material_terms._fresnel), F0 = F(1);
  untinted (t = 1) that is F itself;
- a metal: Cycles' F82 tint (the Metallic BSDF's too): Schlick's curve from the base colour
  to white, less b cos (1 - cos)^6, b solved here from its definition (at cos = 1/7,
  82 degrees, the curve is Schlick's times the tint).

Side by side with Cycles (rough, in a lamp and the sun): tests/blender/test_cycles_glints.py's
tinted plastic and tinted gold."""

import numpy as np
import pytest

from core import Environment, Material, RenderSettings, Scene, ShaderNode, render
from tests.core.test_environment import ball, hits, look_at_ball
from tests.core.test_node_material_terms import _fresnel

pytestmark = pytest.mark.filterwarnings("ignore:invalid value:RuntimeWarning")  # the rim's 0/0
SIZE = 24


def _seen(**inputs):
    return _seen_node(
        ShaderNode("principled", {"Base Color": (0.0, 0.0, 0.0), "Roughness": 0.0, **inputs})
    )


def _seen_node(surface):
    scene = Scene(look_at_ball(), [ball(Material(surface=surface))],
                  environment=Environment(colour=(1.0, 1.0, 1.0)))  # fmt: skip
    settings = RenderSettings(SIZE, SIZE, pixel_samples=1, max_depth=2, environment_samples=4)
    image = render(scene, settings).image[..., :3].astype(float)
    points, inside = hits(SIZE)
    return image[inside], -points[..., 1][inside]


@pytest.mark.parametrize("ior, tint", [(1.5, (1.0, 0.5, 0.2)), (2.2, (0.3, 1.0, 0.0))])
def test_a_tinted_dielectric_reflects_cycles_tinted_fresnel(ior, tint):
    seen, cos = _seen(IOR=ior, **{"Specular Tint": tint})
    f = _fresnel(cos, 1.0, ior)[:, None]
    f0 = ((ior - 1.0) / (ior + 1.0)) ** 2
    t = np.asarray(tint)[None, :]
    expected = f0 * t + (1.0 - f0 * t) * (f - f0) / (1.0 - f0)
    np.testing.assert_allclose(seen, expected, atol=2e-6)


def test_an_untinted_dielectric_reflects_the_exact_fresnel():
    seen, cos = _seen(IOR=1.7)
    np.testing.assert_allclose(seen, np.repeat(_fresnel(cos, 1.0, 1.7)[:, None], 3, 1), atol=2e-6)


def _schlick(f0, cos):
    return f0 + (1.0 - f0) * (1.0 - cos) ** 5


@pytest.mark.parametrize("kind", ["principled", "metallic"])
def test_a_tinted_metal_follows_cycles_f82_tint(kind):
    base, tint = np.array([0.9, 0.6, 0.3]), np.array([0.5, 0.8, 1.0])
    if kind == "principled":
        inputs = {"Base Color": tuple(base), "Metallic": 1.0, "Specular Tint": tuple(tint)}
        seen, cos = _seen(**inputs)
    else:
        seen, cos = _seen_node(ShaderNode("metallic", {"Base Color": tuple(base),
                                                       "Edge Tint": tuple(tint),
                                                       "Roughness": 0.0}))  # fmt: skip
    c82 = 1.0 / 7.0
    b = _schlick(base, c82) * (1.0 - tint) / (c82 * (1.0 - c82) ** 6)
    c = cos[:, None]
    expected = np.clip(_schlick(base, c) - b * c * (1.0 - c) ** 6, 0.0, 1.0)
    np.testing.assert_allclose(seen, expected, atol=2e-6)
