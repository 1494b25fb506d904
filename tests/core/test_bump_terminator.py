"""The shadow terminator term of a diffuse lit through a bent normal (core.kernels.bent_normal),
against closed forms computed here: a white square facing up, its normal bent by a
world-space Normal Map of a fixed tilt, under a sun at a grazing angle, so every pixel is

    E / pi * cos(bent, L) * term

- "chiang": g = (S.L) / ((B.L)(S.B)), the term -g^3 + g^2 + g below g = 1 (Chiang, Li,
  Burley 2019);
- "conty": the GGX masking 2 / (1 + sqrt(1 + a^2 tan^2 i)), a^2 = tan^2(d) / 8, d the bend
  and i the light's angle to the smooth normal (Conty Estevez, Lecocq, Stein 2019);
- "none", and a material whose bend is its displacement: the term is 1;
- a material without Bump Map Correction: none under Chiang's rule, and under Conty's only
  its test that the light and the bent normal are on one side of the smooth surface.
A Normal Map's Strength mixes the mapped vector, unit or not, with the normal before making
it unit, as Cycles does (measured against Cycles in tests/blender/test_cycles_textures.py)."""

import math

import numpy as np
import pytest

from core import (
    Camera,
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

SQUARE = np.array([[-1.0, -1.0, 0.0], [1.0, -1.0, 0.0], [1.0, 1.0, 0.0], [-1.0, 1.0, 0.0]])
UP = np.array([0.0, 0.0, 1.0])
IRRADIANCE = 3.0


def _unit(v):
    v = np.asarray(v, float)
    return v / np.linalg.norm(v)


def _rendered(colour, light_from, terminator, bump_rule="corrected", strength=1.0):
    """The square's mean pixel: a white Diffuse whose Normal is a World-space Normal Map of
    `colour`, lit by a sun from unit direction `light_from`."""
    mapped = ShaderNode("normal_map", {"Color": colour, "Strength": strength},
                        settings={"space": "WORLD"})  # fmt: skip
    diffuse = ShaderNode("diffuse", {"Color": (1.0, 1.0, 1.0), "Normal": Link(mapped, "Normal")})
    material = Material(surface=diffuse, bump_rule=bump_rule)
    square = Mesh("Square", material, np.eye(4), mesh=TriangleMesh(SQUARE, [[0, 1, 2], [0, 2, 3]]))
    camera = Camera(eye=(0.0, 0.0, 5.0), view=(0.0, 0.0, -1.0), up=(0.0, 1.0, 0.0),
                    projection="orthographic", ortho_height=1.0)  # fmt: skip
    sun = SunLight(direction=tuple(-np.asarray(light_from)), irradiance=(IRRADIANCE,) * 3)
    settings = RenderSettings(4, 4, pixel_samples=1, bump_terminator=terminator)
    image = render(Scene(camera, [square], lights=[sun]), settings).image
    return float(image[..., 0].mean())


def _chiang(bent, light):
    g = (UP @ light) / ((bent @ light) * (UP @ bent))
    return 1.0 if g >= 1.0 else (0.0 if g < 0.0 else -(g**3) + g**2 + g)


def _conty(bent, light):
    cos_d, cos_i = UP @ bent, UP @ light
    alpha2 = min(0.125 * (1.0 / cos_d**2 - 1.0), 1.0)
    return 2.0 / (1.0 + math.sqrt(1.0 + alpha2 * (1.0 / cos_i**2 - 1.0)))


# a 30-degree tilt towards +x; a sun 80 degrees from straight up, on the +x side
TILT = np.array([math.sin(math.radians(30.0)), 0.0, math.cos(math.radians(30.0))])
GRAZING = np.array([math.sin(math.radians(80.0)), 0.0, math.cos(math.radians(80.0))])


def _colour(n):
    return tuple((np.asarray(n) + 1.0) / 2.0)


@pytest.mark.parametrize(
    "terminator, rule, term",
    [
        ("chiang", "corrected", _chiang),
        ("conty", "corrected", _conty),
        ("none", "corrected", None),
        ("chiang", "displaced", None),
        ("conty", "displaced", None),
        ("chiang", "uncorrected", None),
        ("conty", "uncorrected", None),
    ],
)
def test_a_tilted_square_in_a_grazing_sun_gets_each_rules_term(terminator, rule, term):
    lambert = IRRADIANCE / math.pi * (TILT @ GRAZING)
    expected = lambert * (term(TILT, GRAZING) if term is not None else 1.0)
    assert _rendered(_colour(TILT), GRAZING, terminator, rule) == pytest.approx(expected, 1e-5)
    if term is not None:  # the premise: the term takes a share off here
        assert expected < 0.95 * lambert


def test_conty_lights_nothing_through_a_bent_normal_across_the_smooth_surface():
    """A light 10 degrees below the smooth surface's horizon, a normal bent 70 degrees
    towards it (as an interpolated normal's surface may see, the geometric one still lit):
    Conty's side test gives nothing, with Bump Map Correction or without, and keeps glints
    dark too; Chiang's term is nothing there (g < 0); no rule, the whole cosine."""
    from core.kernels.bent_normal import on_smooth_side, terminator_term
    from core.vocabulary import (
        TERMINATOR_CHIANG,
        TERMINATOR_CONTY,
        TERMINATOR_NONE,
        TERMINATOR_SIDES,
    )

    below = (math.sin(math.radians(100.0)), 0.0, math.cos(math.radians(100.0)))
    bent = (math.sin(math.radians(70.0)), 0.0, math.cos(math.radians(70.0)))
    up = (0.0, 0.0, 1.0)
    assert np.dot(bent, below) > 0.5  # the premise: the bent normal faces the light
    for model in (TERMINATOR_CONTY, TERMINATOR_SIDES, TERMINATOR_CHIANG):
        assert terminator_term(up, bent, below, model) == 0.0
    assert terminator_term(up, bent, below, TERMINATOR_NONE) == 1.0
    assert not on_smooth_side(up, bent, below, TERMINATOR_CONTY)
    assert on_smooth_side(up, bent, below, TERMINATOR_CHIANG)  # Chiang's has no side test
    above = (math.sin(math.radians(60.0)), 0.0, math.cos(math.radians(60.0)))
    assert terminator_term(up, bent, above, TERMINATOR_SIDES) == 1.0  # sides only: no softening
    assert on_smooth_side(up, bent, above, TERMINATOR_CONTY)


def test_strength_mixes_the_mapped_vector_before_it_is_unit():
    """A tangent-space colour whose 2c - 1 is 0.78 long, at Strength 0.6, in World space
    (made unit first, as Cycles' World space is) and, through an object of identity
    transform, in Object space (mixed as it is, as Cycles 4 mixes it; made unit first, as
    Cycles 3 did: strength_mix "UNIT")."""
    raw = np.array([0.25, 0.53, 0.51])  # 2c - 1, not unit
    colour = tuple((raw + 1.0) / 2.0)
    for space, mix, mapped in (("WORLD", "VECTOR", _unit(raw)), ("OBJECT", "VECTOR", raw),
                               ("OBJECT", "UNIT", _unit(raw))):  # fmt: skip
        node = ShaderNode("normal_map", {"Color": colour, "Strength": 0.6},
                          settings={"space": space, "strength_mix": mix})  # fmt: skip
        shifted = ShaderNode("vector_math", {"A": Link(node, "Normal"), "B": (1.0, 1.0, 1.0)})
        half = ShaderNode("vector_math", {"A": Link(shifted, "Vector"), "Scale": 0.5},
                          settings={"operation": "SCALE"})  # fmt: skip
        glow = Material(surface=ShaderNode("emission", {"Color": Link(half, "Vector")}))
        square = Mesh("Square", glow, np.eye(4), mesh=TriangleMesh(SQUARE, [[0, 1, 2], [0, 2, 3]]))
        camera = Camera(eye=(0.0, 0.0, 5.0), view=(0.0, 0.0, -1.0), up=(0.0, 1.0, 0.0),
                        projection="orthographic", ortho_height=1.0)  # fmt: skip
        image = render(Scene(camera, [square]), RenderSettings(4, 4, pixel_samples=1)).image
        expected = _unit(UP + (mapped - UP) * 0.6)
        np.testing.assert_allclose(2.0 * image[..., :3].mean(axis=(0, 1)) - 1.0, expected,
                                   atol=1e-5)  # fmt: skip
