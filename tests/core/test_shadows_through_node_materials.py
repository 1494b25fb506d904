"""Shadow rays through node materials whose transparency varies over the surface
(core.kernels.shadow_log), against closed forms: a leaf card's image alpha passes
1 - alpha at each texel; a sphere whose Transparent mix follows its object X passes the
product of the factor at both crossings; the same spheres as CSG operands; a textured
material that can never let light through still blocks outright, as a constant does; and
soft shadows with their passes, against the constant-share path."""

import math

import numpy as np
import pytest

from core import (
    AreaLight,
    Camera,
    Csg,
    Link,
    Material,
    Mesh,
    PanelLight,
    RenderSettings,
    Scene,
    ShaderNode,
    Sphere,
    SunLight,
    Texture,
    TriangleMesh,
    render,
)
from core.compile import pack_scene
from core.kernels.shadow_log import SHADOW_VARIES
from tests.support.probe import light_by_full_rule, packed_shapes

TEXELS = 8


def _alpha_mask():
    """Alpha per texel, 0, 0.3 or 1 (Closest lookups: each texel's own)."""
    rng = np.random.default_rng(5)
    return rng.choice([0.0, 0.3, 1.0], size=(TEXELS, TEXELS))


def _card_material(mask):
    pixels = np.zeros((TEXELS, TEXELS, 4))
    pixels[..., 1] = 0.7
    pixels[..., 3] = mask
    image = ShaderNode("image", settings={"texture": Texture(pixels=pixels, srgb=False),
                                          "interpolation": "Closest"})  # fmt: skip
    principled = ShaderNode("principled", {"Base Color": Link(image, "Color"),
                                           "Alpha": Link(image, "Alpha")})  # fmt: skip
    return Material(name="Leaf", surface=principled)


def _card(mask, z=1.0, seen_by_camera=True):
    """A 2 x 2 card at height z, its UVs across it; the image's row 0 at its top (+y)."""
    vertices = np.array([[-1, -1, z], [1, -1, z], [1, 1, z], [-1, 1, z]], float)
    mesh = TriangleMesh(vertices, np.array([[0, 1, 2], [0, 2, 3]]),
                        vertex_uvs=(vertices[:, :2] + 1.0) / 2.0)  # fmt: skip
    return Mesh("Card", _card_material(mask), mesh=mesh, seen_by_camera=seen_by_camera)


def _texel_centres():
    """(x, y) of each texel's centre on the card, in the image's row order."""
    c = (np.arange(TEXELS) + 0.5) / TEXELS * 2.0 - 1.0
    x, y = np.meshgrid(c, -c)
    return x, y


def test_a_shadow_ray_through_a_leaf_card_passes_one_minus_its_texels_alpha():
    mask = _alpha_mask()
    packed = packed_shapes(_card(mask))
    assert packed.geometry.shape_transparency[0] == SHADOW_VARIES
    x, y = _texel_centres()
    passed = np.array([
        [light_by_full_rule(packed, (x[j, i], y[j, i], 0.0), (0.0, 0.0, 1.0), 5.0)
         for i in range(TEXELS)] for j in range(TEXELS)
    ])  # fmt: skip
    np.testing.assert_allclose(passed, 1.0 - mask, atol=1e-6)
    # and a ray that stops short of the card passes everything
    assert light_by_full_rule(packed, (0.1, 0.1, 0.0), (0.0, 0.0, 1.0), 0.9) == 1.0


def test_a_floor_under_a_leaf_card_shows_the_cards_alpha_as_its_shadow():
    """Rendered: the card hidden from the camera (Ray Visibility > Camera off), a sun
    straight down; each floor pixel under the card is lit by 1 - alpha of its texel."""
    mask = _alpha_mask()
    floor_vertices = np.array([[-2, -2, 0], [2, -2, 0], [2, 2, 0], [-2, 2, 0]], float)
    floor = Mesh("Floor", Material(diffuse=(1.0, 1.0, 1.0), specular=(0.0, 0.0, 0.0)),
                 mesh=TriangleMesh(floor_vertices, np.array([[0, 1, 2], [0, 2, 3]])))  # fmt: skip
    camera = Camera(eye=(0.0, 0.0, 5.0), view=(0.0, 0.0, -1.0), up=(0.0, 1.0, 0.0),
                    projection="orthographic", ortho_height=2.0)  # fmt: skip
    sun = SunLight(direction=(0.0, 0.0, -1.0), irradiance=(math.pi,) * 3)
    scene = Scene(camera, [floor, _card(mask, seen_by_camera=False)], [sun])
    out = render(scene, RenderSettings(32, 32, pixel_samples=1)).image[..., 0].astype(float)
    expected = np.kron(1.0 - mask, np.ones((4, 4)))
    np.testing.assert_allclose(out, expected, atol=1e-6)


def x_mix_material(closure=None):
    """A Mix Shader of Diffuse and `closure` (a Transparent BSDF unless given) whose factor
    is 0.5 + 0.4 X (object X): a shadow ray crossing the surface at object X passes
    0.5 + 0.4 X there (under the glass-shadow rule, tests/core/test_glass_shadows.py)."""
    coords = ShaderNode("tex_coord")
    separate = ShaderNode("separate", {"Vector": Link(coords, "Object")})
    factor = ShaderNode("math", {"A": Link(separate, "X"), "B": 0.4, "C": 0.5},
                        {"operation": "MULTIPLY_ADD"})  # fmt: skip
    mix = ShaderNode("mix_shader", {
        "Fac": Link(factor, "Value"),
        "Shader A": Link(ShaderNode("diffuse"), "BSDF"),
        "Shader B": Link(closure or ShaderNode("transparent"), "BSDF"),
    })  # fmt: skip
    return Material(name="Veil", surface=mix)


def _factor(x):
    return 0.5 + 0.4 * x


def test_a_ray_through_a_varying_sphere_passes_the_product_at_both_crossings():
    packed = packed_shapes(Sphere("Veil", x_mix_material(), np.eye(4)))
    assert packed.geometry.shape_transparency[0] == SHADOW_VARIES
    for x0 in (-0.7, 0.0, 0.45):
        # along z: both crossings at X = x0
        passed = light_by_full_rule(packed, (x0, 0.0, -3.0), (0.0, 0.0, 1.0), 6.0)
        assert math.isclose(passed, _factor(x0) ** 2, rel_tol=1e-9), (x0, passed)
    # along x: at X = -1 and X = +1; a ray ending inside crosses once
    passed = light_by_full_rule(packed, (-3.0, 0.0, 0.0), (1.0, 0.0, 0.0), 6.0)
    assert math.isclose(passed, _factor(-1.0) * _factor(1.0), rel_tol=1e-9)
    passed = light_by_full_rule(packed, (0.0, 0.0, 0.0), (1.0, 0.0, 0.0), 6.0)
    assert math.isclose(passed, _factor(1.0), rel_tol=1e-9)


def test_varying_operands_of_a_csg_union_pass_the_product_of_their_crossings():
    """Two such spheres, apart, united: a ray along x through both crosses each twice."""
    veil = x_mix_material()
    left = Sphere("Left", veil, _moved(-2.0))
    right = Sphere("Right", veil, _moved(2.0))
    packed = packed_shapes(Csg("Pair", veil, np.eye(4), operation="union", left=left,
                               right=right))  # fmt: skip
    passed = light_by_full_rule(packed, (-5.0, 0.0, 0.3), (1.0, 0.0, 0.0), 10.0)
    x = math.sqrt(1.0 - 0.3**2)  # object X of the crossings, the same in each sphere
    assert math.isclose(passed, (_factor(-x) * _factor(x)) ** 2, rel_tol=1e-9)


def _moved(x):
    transform = np.eye(4)
    transform[0, 3] = x
    return transform


def test_a_textured_material_that_lets_no_light_by_full_rule_blocks_shadows_outright():
    """Its program varies over the surface but no closure of it passes light: share 0, as
    an opaque constant material's, and no program is run for its shadows."""
    coords = ShaderNode("tex_coord")
    checker = ShaderNode("checker", {"Vector": Link(coords, "Object")})
    diffuse = ShaderNode("diffuse", {"Color": Link(checker, "Color")})
    packed = pack_scene(
        Scene(shapes=[Sphere("Checked", Material(name="Checked", surface=diffuse), np.eye(4))]),
        RenderSettings(8, 8, pixel_samples=1),
    )
    assert packed.materials.shader_range[0, 0] >= 0  # a program, run per hit
    assert packed.geometry.shape_transparency[0] == 0.0
    assert light_by_full_rule(packed, (0.0, 0.0, -3.0), (0.0, 0.0, 1.0), 6.0) == 0.0


def _constant_card(alpha, seen_by_camera=False):
    """The card of `_card` with one Alpha for the whole of it, not from an image: a
    constant material, whose share the shadow path multiplies in directly."""
    vertices = np.array([[-1, -1, 1], [1, -1, 1], [1, 1, 1], [-1, 1, 1]], float)
    mesh = TriangleMesh(vertices, np.array([[0, 1, 2], [0, 2, 3]]))
    principled = ShaderNode("principled", {"Base Color": (0.0, 0.7, 0.0), "Alpha": alpha})
    return Mesh("Card", Material(name="Leaf", surface=principled), mesh=mesh,
                seen_by_camera=seen_by_camera)  # fmt: skip


@pytest.mark.parametrize("samples, adaptive", [(16, False), (24, True)])
def test_soft_shadows_and_their_passes_through_a_varying_card_match_a_constant_one(
    samples, adaptive
):
    """An area light (16 shadow rays a point; 24 with adaptive soft shadows, whose probes
    decide in the first pass and again in the replay), a panel light in watts and a sun of some
    angle over a floor, the card between: lit through an image whose alpha is 0.3 at every
    texel (its program answered per crossing, the point lit again in replay), the floor
    and its Shadow and Diffuse passes are those of the same card with Alpha 0.3 set
    once (a constant share): the same samples, the same rule, the other code path (to the
    float32 picture's rounding: the shares are multiplied in another order)."""
    floor_vertices = np.array([[-2, -2, 0], [2, -2, 0], [2, 2, 0], [-2, 2, 0]], float)
    floor = Mesh("Floor", Material(diffuse=(1.0, 1.0, 1.0), specular=(0.0, 0.0, 0.0)),
                 mesh=TriangleMesh(floor_vertices, np.array([[0, 1, 2], [0, 2, 3]])))  # fmt: skip
    camera = Camera(eye=(0.0, 0.0, 5.0), view=(0.0, 0.0, -1.0), up=(0.0, 1.0, 0.0),
                    projection="orthographic", ortho_height=3.0)  # fmt: skip
    lights = [
        AreaLight(centre=(0.3, 0.0, 3.0), edge_u=(1.0, 0.0, 0.0), edge_v=(0.0, 1.0, 0.0),
                  intensity=(0.6, 0.6, 0.6)),
        PanelLight(centre=(-0.5, 0.4, 2.5), edge_u=(0.8, 0.0, 0.0), edge_v=(0.0, 0.8, 0.0),
                   power=(20.0, 20.0, 20.0)),
        SunLight(direction=(0.2, 0.1, -1.0), irradiance=(1.0, 1.0, 1.0), angle=10.0),
    ]  # fmt: skip
    settings = RenderSettings(24, 24, pixel_samples=1, shadow_samples=samples,
                              adaptive_shadows=adaptive, passes=("shadow", "diffuse"))  # fmt: skip
    varying = _card(np.full((TEXELS, TEXELS), 0.3), seen_by_camera=False)
    through_image = render(Scene(camera, [floor, varying], lights), settings)
    through_constant = render(Scene(camera, [floor, _constant_card(0.3)], lights), settings)
    shadowed = (
        through_constant.image[..., 0]
        < render(Scene(camera, [floor], lights), settings).image[..., 0] - 1e-3
    )
    assert shadowed.mean() > 0.3  # the card's shadow covers much of the floor
    np.testing.assert_allclose(through_image.image, through_constant.image, rtol=1e-6, atol=1e-7)
    for name in ("shadow", "diffuse"):
        np.testing.assert_allclose(
            through_image.passes[name], through_constant.passes[name], rtol=1e-6, atol=1e-7
        )


def test_a_shading_point_whose_varying_crossings_overflow_says_so():
    """Forty stacked half-transparent cards between a floor and an area light of 32
    shadow rays: 1280 crossings at each floor point, more than a point can hold. The render
    warns, naming what overflowed; nothing passes silently."""
    layers = 40
    corners = np.array([[-1, -1, 0], [1, -1, 0], [1, 1, 0], [-1, 1, 0]], float)
    vertices = np.concatenate([corners + (0.0, 0.0, 1.0 + 0.02 * k) for k in range(layers)])
    faces = np.concatenate([np.array([[0, 1, 2], [0, 2, 3]]) + 4 * k for k in range(layers)])
    uvs = (vertices[:, :2] + 1.0) / 2.0
    mesh = TriangleMesh(vertices, faces, vertex_uvs=uvs)
    half = _card_material(np.full((TEXELS, TEXELS), 0.5))
    stack = Mesh("Stack", half, mesh=mesh, seen_by_camera=False)
    floor_vertices = np.array([[-2, -2, 0], [2, -2, 0], [2, 2, 0], [-2, 2, 0]], float)
    floor = Mesh("Floor", Material(diffuse=(1.0, 1.0, 1.0)),
                 mesh=TriangleMesh(floor_vertices, np.array([[0, 1, 2], [0, 2, 3]])))  # fmt: skip
    camera = Camera(eye=(0.0, 0.0, 5.0), view=(0.0, 0.0, -1.0), up=(0.0, 1.0, 0.0),
                    projection="orthographic", ortho_height=0.5)  # fmt: skip
    light = AreaLight(centre=(0.0, 0.0, 3.0), edge_u=(0.2, 0.0, 0.0), edge_v=(0.0, 0.2, 0.0))
    settings = RenderSettings(1, 1, pixel_samples=1, shadow_samples=32)
    result = render(Scene(camera, [floor, stack], [light]), settings)
    # 25 rays' 40 crossings fit the 1024 listed; the other 7 are blocked and counted
    said = [w for w in result.warnings if "varies than a shading point can hold" in w]
    assert said and said[0].startswith("7 shadow rays"), result.warnings
