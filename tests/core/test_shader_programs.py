"""Shader graphs (core.model.shader) run per hit as programs, against independent answers:
an image through a program gives the very pixels of the report's texture path; Checker,
Gradient, Mapping, Math and Mix Color against their formulas computed here in numpy; a
graph with nothing varying is folded into the table (no program left) and renders as the
material it makes; a Mix Shader whose factor is a texture mixes per hit."""

import numpy as np
import pytest

from core import Link, Material, RenderSettings, Scene, ShaderNode, Texture, render
from core.compile import compile_scene
from core.compile.materials import folded_row
from core.model.shader import MATH_OPERATIONS
from tests.core.test_environment import ball, hits, look_at_ball
from tests.core.test_node_material_terms import _fresnel

SIZE = 16


def _image(size=SIZE, material=None, environment_colour=1.0):
    from core import Environment

    scene = Scene(look_at_ball(), [ball(material)],
                  environment=Environment(colour=(environment_colour,) * 3))  # fmt: skip
    settings = RenderSettings(size, size, pixel_samples=1, environment_samples=4, max_depth=2)
    return render(scene, settings).image[..., :3].astype(float), scene, settings


def _node(kind, **inputs):
    settings = {k[4:]: v for k, v in inputs.items() if k.startswith("set_")}
    given = {k.replace("_", " "): v for k, v in inputs.items() if not k.startswith("set_")}
    return ShaderNode(kind, given, settings)


def _diffuse(colour):
    return Material(surface=_node("diffuse", Color=colour))


def _stripes():
    rng = np.random.default_rng(3)
    return rng.uniform(0.0, 1.0, (6, 10, 3))


def test_an_image_through_a_program_gives_the_texture_paths_very_pixels():
    pixels = _stripes()
    texture = Texture(pixels=pixels, srgb=False)
    image = ShaderNode("image", settings={"texture": texture})
    programmed, _, _ = _image(material=_diffuse(Link(image, "Color")))
    report, _, _ = _image(material=Material(texture=texture, specular=(0.0, 0.0, 0.0)))
    np.testing.assert_array_equal(programmed, report)


def test_a_graph_with_nothing_varying_is_folded_into_the_table():
    principled = _node("principled", Base_Color=(0.9, 0.6, 0.2), Metallic=1.0, Roughness=0.0)
    material = Material(surface=principled)
    _, scene, settings = _image(material=material)
    table = compile_scene(scene, settings).packed.materials
    row = folded_row(table, 0)
    assert not row["programmed"]
    np.testing.assert_allclose(row["mirror_colour"], (0.9, 0.6, 0.2))
    np.testing.assert_allclose(row["mirror_edge"], (1.0, 1.0, 1.0))
    assert row["reflectivity"] == 1.0 and np.all(row["diffuse"] == 0.0)


def _generated(points):
    """Blender's Generated coordinates on the unit ball: its box [-1, 1]^3 to [0, 1]^3."""
    return (points + 1.0) / 2.0


def test_checker_follows_blenders_squares_on_generated_coordinates():
    checker = _node("checker", Color1=(1.0, 0.0, 0.0), Color2=(0.0, 0.0, 1.0), Scale=3.0)
    image, _, _ = _image(material=_diffuse(Link(checker, "Color")))
    points, inside = hits(SIZE)
    p = _generated(points) * 3.0
    p = (p + 0.000001) * 0.999999
    cells = np.abs(np.floor(p)).astype(int) % 2
    first = (cells[..., 0] == cells[..., 1]) == (cells[..., 2] == 1)
    red = image[..., 0] > image[..., 2]
    assert np.array_equal(red[inside], first[inside])


@pytest.mark.parametrize("kind", ["LINEAR", "QUADRATIC", "EASING", "DIAGONAL", "SPHERICAL"])
def test_a_gradient_through_a_mapping_node_matches_its_formula(kind):
    # the furnace (a white World of radiance 1) gives a diffuse ball its albedo exactly
    mapping = _node("mapping", Vector=None, Location=(0.1, -0.2, 0.3), Scale=(2.0, 1.0, 0.5),
                    set_type="POINT")  # fmt: skip
    coords = ShaderNode("tex_coord")
    mapping.inputs["Vector"] = Link(coords, "Object")
    gradient = _node("gradient", Vector=Link(mapping, "Vector"), set_type=kind)
    image, _, _ = _image(material=_diffuse(Link(gradient, "Color")))
    points, inside = hits(SIZE)
    x, y, z = (points * (2.0, 1.0, 0.5) + (0.1, -0.2, 0.3)).transpose(2, 0, 1)
    expected = {
        "LINEAR": x,
        "QUADRATIC": np.maximum(x, 0.0) ** 2,
        "EASING": 3 * np.clip(x, 0, 1) ** 2 - 2 * np.clip(x, 0, 1) ** 3,
        "DIAGONAL": (x + y) / 2.0,
        "SPHERICAL": np.maximum(0.999999 - np.sqrt(x * x + y * y + z * z), 0.0),
    }[kind]
    np.testing.assert_allclose(image[..., 0][inside], np.clip(expected, 0, 1)[inside], atol=1e-9)


def test_math_and_mix_color_compute_as_blender_defines_them():
    coords = ShaderNode("tex_coord")
    separate = _node("separate", Vector=Link(coords, "Object"))
    # u = 0.5 + x / 2 in [0, 1]: through Math (multiply-add), Mix Color Multiply and Invert
    u = _node("math", A=Link(separate, "X"), B=0.5, C=0.5, set_operation="MULTIPLY_ADD")
    mixed = _node("mix_color", Fac=Link(u, "Value"), A=(0.2, 0.4, 0.8), B=(0.5, 1.0, 0.25),
                  set_blend="MULTIPLY")  # fmt: skip
    inverted = _node("invert", Fac=0.25, Color=Link(mixed, "Color"))
    image, _, _ = _image(material=_diffuse(Link(inverted, "Color")))
    points, inside = hits(SIZE)
    t = 0.5 * points[..., 0:1] + 0.5
    a, b = np.array([0.2, 0.4, 0.8]), np.array([0.5, 1.0, 0.25])
    mix = a * (1.0 - t) + (a * b) * t
    expected = mix * 0.75 + (1.0 - mix) * 0.25
    np.testing.assert_allclose(image[inside], expected[inside], atol=1e-9)


def test_a_textured_mix_factor_mixes_two_shaders_per_hit():
    """Half the ball a white mirror, half black diffuse, split by a Math node on the Object
    x: the mirror shows the World (1), the diffuse black shows nothing."""
    coords = ShaderNode("tex_coord")
    separate = _node("separate", Vector=Link(coords, "Object"))
    right = _node("math", A=Link(separate, "X"), B=0.0, set_operation="GREATER_THAN")
    mirror = _node("glossy", Color=(1.0, 1.0, 1.0), Roughness=0.0)
    black = _node("diffuse", Color=(0.0, 0.0, 0.0))
    mix = ShaderNode("mix_shader", {"Fac": Link(right, "Value"), "Shader A": Link(black),
                                    "Shader B": Link(mirror)})  # fmt: skip
    image, _, _ = _image(material=Material(surface=mix), environment_colour=0.5)
    points, inside = hits(SIZE)
    on_right = inside & (points[..., 0] > 0.0)
    on_left = inside & (points[..., 0] < 0.0)
    np.testing.assert_allclose(image[on_right], 0.5)
    np.testing.assert_allclose(image[on_left], 0.0)


def test_a_varying_principled_coat_is_the_exact_fresnel_per_hit():
    """A Principled of black base whose roughness is 0 on one side only: the coat there
    reflects the World by the exact Fresnel of IOR 1.5 at every pixel."""
    coords = ShaderNode("tex_coord")
    separate = _node("separate", Vector=Link(coords, "Object"))
    rough = _node("math", A=Link(separate, "X"), B=0.0, set_operation="LESS_THAN")
    principled = _node("principled", Base_Color=(0.0, 0.0, 0.0), Roughness=Link(rough, "Value"),
                       IOR=1.5)  # fmt: skip
    image, _, _ = _image(material=Material(surface=principled))
    points, inside = hits(SIZE)
    smooth = inside & (points[..., 0] > 0.05)
    cos = -points[..., 1]
    np.testing.assert_allclose(image[..., 0][smooth], _fresnel(cos, 1.0, 1.5)[smooth], rtol=1e-6)


def _reference_math(operation, a, b, c):
    """Blender's Math node, written again here from its manual (Cycles' safe variants:
    division and the like by zero give 0)."""
    import math

    table = {
        "ADD": a + b, "SUBTRACT": a - b, "MULTIPLY": a * b, "DIVIDE": a / b if b else 0.0,
        "MULTIPLY_ADD": a * b + c, "MINIMUM": min(a, b), "MAXIMUM": max(a, b),
        "LESS_THAN": float(a < b), "GREATER_THAN": float(a > b), "ABSOLUTE": abs(a),
        "SQRT": math.sqrt(a) if a > 0 else 0.0, "FLOOR": math.floor(a), "CEIL": math.ceil(a),
        "FRACT": a - math.floor(a), "MODULO": math.fmod(a, b) if b else 0.0,
        "SINE": math.sin(a), "COSINE": math.cos(a), "SNAP": math.floor(a / b) * b if b else 0.0,
        "ROUND": math.floor(a + 0.5), "SIGN": float(np.sign(a)), "EXPONENT": math.exp(a),
        "TRUNC": math.trunc(a), "INVERSE_SQRT": 1 / math.sqrt(a) if a > 0 else 0.0,
        "FLOORED_MODULO": a - math.floor(a / b) * b if b else 0.0, "TANGENT": math.tan(a),
        "ARCSINE": math.asin(max(-1.0, min(1.0, a))), "ARCCOSINE": math.acos(max(-1, min(1, a))),
        "ARCTANGENT": math.atan(a), "ARCTAN2": math.atan2(a, b), "SINH": math.sinh(a),
        "COSH": math.cosh(a), "TANH": math.tanh(a), "RADIANS": math.radians(a),
        "DEGREES": math.degrees(a),
        "COMPARE": float(abs(a - b) <= max(c, 1e-5)),
        "WRAP": a - (b - c) * math.floor((a - c) / (b - c)) if b != c else c,
    }  # fmt: skip
    if operation == "POWER":
        return a**b if a > 0 or (a < 0 and b == int(b)) else (0.0 if a or b > 0 else 1.0)
    if operation == "LOGARITHM":
        return math.log(a) / math.log(b) if a > 0 and b > 0 and b != 1 else 0.0
    return table.get(operation)


@pytest.mark.parametrize("operation", MATH_OPERATIONS)
def test_each_math_operation_is_blenders(operation):
    from core.kernels.shader_values import math_node

    code = MATH_OPERATIONS.index(operation)
    for a, b, c in [(0.7, 0.3, 0.1), (-1.3, 2.0, 0.5), (2.5, -0.75, 1.0), (0.0, 0.0, 0.0),
                    (5.0, 5.0, 0.0), (-0.4, 1.0, -1.0)]:  # fmt: skip
        expected = _reference_math(operation, a, b, c)
        if expected is None:  # ping-pong and the smooth minimum and maximum: below
            continue
        assert math_node(code, a, b, c) == pytest.approx(expected, abs=1e-12), (a, b, c)


def test_ping_pong_and_the_smooth_minimum_follow_their_shapes():
    from core.kernels.shader_values import M_PINGPONG, M_SMOOTH_MAX, M_SMOOTH_MIN, math_node

    # ping-pong of period 2b: up from 0 to b and back down
    for a, expected in [(0.25, 0.25), (1.0, 1.0), (1.5, 0.5), (2.0, 0.0), (-0.5, 0.5)]:
        assert math_node(M_PINGPONG, a, 1.0, 0.0) == pytest.approx(expected)
    # far apart the smooth minimum is the minimum; equal, it is min - k/6
    assert math_node(M_SMOOTH_MIN, 0.0, 5.0, 1.0) == 0.0
    assert math_node(M_SMOOTH_MIN, 2.0, 2.0, 1.2) == pytest.approx(2.0 - 1.2 / 6.0)
    assert math_node(M_SMOOTH_MAX, 2.0, 2.0, 1.2) == pytest.approx(2.0 + 1.2 / 6.0)


def test_a_graph_too_large_for_the_stack_is_refused_by_name():
    from core import SceneError
    from core.kernels.shader_program import SHADER_STACK

    def adds(depth):  # a balanced tree of Math nodes, three slots each
        if depth == 0:
            return 0.001
        return Link(_node("math", A=adds(depth - 1), B=adds(depth - 1)), "Value")

    assert SHADER_STACK < 2**11 * 3
    material = Material(name="Tower", surface=_node("emission", Strength=adds(11)))
    with pytest.raises(SceneError, match=r"material 'Tower'.*surface.*numbers at a hit"):
        _image(material=material)


def test_a_graph_too_deep_to_walk_is_refused_by_name():
    from core import SceneError
    from core.model.shader import MAX_GRAPH_DEPTH

    value = 0.5
    for _ in range(MAX_GRAPH_DEPTH + 5):
        value = Link(_node("math", A=value), "Value")
    material = Material(name="Well", surface=_node("emission", Strength=value))
    with pytest.raises(SceneError, match=r"material 'Well'.*deep"):
        _image(material=material)


@pytest.mark.parametrize(
    "setting, value, message",
    [
        ("offset", 1.5, r"offset: got 1.5; use a number from 0.0 to 1.0"),
        ("squash", -1.0, r"squash: got -1.0; use a number from 0.0 to 99.0"),
        ("offset_frequency", 0, r"offset_frequency: got 0; use a whole number from 1 to 99"),
        ("squash_frequency", 2.5, r"squash_frequency: got 2.5; use a whole number from 1 to 99"),
    ],
)
def test_a_brick_texture_outside_blenders_ranges_is_refused_by_name(setting, value, message):
    """Brick's Offset, Squash and their frequencies: Blender's own ranges; a frequency of 0
    would divide by zero in the kernel."""
    from core import SceneError

    brick = ShaderNode("brick", settings={setting: value})
    material = Material(name="Wall", surface=_node("emission", Color=Link(brick, "Color")))
    with pytest.raises(SceneError, match=rf"material 'Wall'.*{message}"):
        _image(material=material)


def _lit_plane(surface, light_direction=(0.0, 0.0, -1.0)):
    """A mesh plane z = 0 with UVs along x and y, seen from above, lit by a sun of
    irradiance pi: a white Lambertian pixel shows n.l for its shading normal n."""
    from core import Camera, Mesh, SunLight, TriangleMesh

    vertices = np.array([[-2, -2, 0], [2, -2, 0], [2, 2, 0], [-2, 2, 0]], float)
    mesh = TriangleMesh(vertices, np.array([[0, 1, 2], [0, 2, 3]]),
                        vertex_uvs=(vertices[:, :2] + 2.0) / 4.0)  # fmt: skip
    plane = Mesh("Plane", Material(surface=surface), mesh=mesh)
    camera = Camera(eye=(0.0, 0.0, 5.0), view=(0.0, 0.0, -1.0), up=(0.0, 1.0, 0.0),
                    projection="orthographic", ortho_height=2.0)  # fmt: skip
    sun = SunLight(direction=light_direction, irradiance=(np.pi,) * 3)
    scene = Scene(camera, [plane], [sun])
    return render(scene, RenderSettings(SIZE, SIZE, pixel_samples=1)).image[..., 0].astype(float)


def test_bump_on_a_linear_height_tilts_the_normal_by_its_slope():
    """Height k x with Distance D: Cycles' bump gives the normal (-D k, 0, 1), normalised;
    lit from (-1, 0, -1) a white plane shows n.l."""
    coords = ShaderNode("tex_coord")
    separate = _node("separate", Vector=Link(coords, "Object"))
    k, distance = 0.6, 0.8
    height = _node("math", A=Link(separate, "X"), B=k, set_operation="MULTIPLY")
    bump = _node("bump", Height=Link(height, "Value"), Distance=distance)
    white = ShaderNode("diffuse", {"Color": (1.0, 1.0, 1.0), "Normal": Link(bump, "Normal")})
    image = _lit_plane(white, light_direction=(-1.0, 0.0, -1.0))
    n = np.array([-distance * k, 0.0, 1.0]) / np.hypot(distance * k, 1.0)
    to_light = np.array([1.0, 0.0, 1.0]) / np.sqrt(2.0)
    np.testing.assert_allclose(image, n @ to_light, rtol=1e-6)
    flat = _lit_plane(ShaderNode("diffuse", {"Color": (1.0, 1.0, 1.0)}), (-1.0, 0.0, -1.0))
    np.testing.assert_allclose(flat, to_light[2], rtol=1e-6)  # no bump: the plane's own


def test_a_tangent_space_normal_map_turns_the_normal_in_the_uv_frame():
    """A constant normal-map colour c on a plane whose u runs along x and v along y: the
    normal is 2c - 1 in (x, y, z), normalised, and at Strength 0.5 that vector as it is
    (not unit) mixed halfway with (0, 0, 1), then normalised, as Cycles mixes it."""
    colour = (0.8, 0.35, 0.9)
    m = 2.0 * np.array(colour) - 1.0
    for strength in (1.0, 0.5):
        normal_map = _node("normal_map", Color=colour, Strength=strength)
        white = ShaderNode("diffuse", {"Color": (1.0, 1.0, 1.0),
                                       "Normal": Link(normal_map, "Normal")})  # fmt: skip
        image = _lit_plane(white)  # lit straight down: the pixel is n.z
        n = m / np.linalg.norm(m)
        if strength != 1.0:
            n = np.array([0.0, 0.0, 1.0]) + (m - (0.0, 0.0, 1.0)) * strength
            n /= np.linalg.norm(n)
        np.testing.assert_allclose(image, n[2], rtol=1e-6)


def test_an_images_alpha_cuts_the_surface_exactly_at_its_texels():
    """A leaf card: an 8 x 8 image whose alpha is 0 or 1 per texel (Closest) feeding a
    Principled BSDF's Alpha. Seen straight on, 4 x 4 pixels a texel, each pixel shows the
    card or, through the cut, the World behind: the mask's own texels, every one."""
    from core import Camera, Environment, Mesh, TriangleMesh

    rng = np.random.default_rng(11)
    mask = rng.uniform(size=(8, 8)) < 0.5
    pixels = np.zeros((8, 8, 4))
    pixels[..., 0] = 1.0  # the card is red where it stays
    pixels[..., 3] = mask
    image = ShaderNode("image", settings={"texture": Texture(pixels=pixels, srgb=False),
                                          "interpolation": "Closest"})  # fmt: skip
    card = ShaderNode("principled", {"Base Color": (0.0, 0.0, 0.0), "Alpha": Link(image, "Alpha"),
                                     "Emission Color": Link(image, "Color"),
                                     "Emission Strength": 1.0, "Specular": 0.0})  # fmt: skip
    vertices = np.array([[-1, -1, 0], [1, -1, 0], [1, 1, 0], [-1, 1, 0]], float)
    mesh = TriangleMesh(vertices, np.array([[0, 1, 2], [0, 2, 3]]),
                        vertex_uvs=(vertices[:, :2] + 1.0) / 2.0)  # fmt: skip
    camera = Camera(eye=(0.0, 0.0, 5.0), view=(0.0, 0.0, -1.0), up=(0.0, 1.0, 0.0),
                    projection="orthographic", ortho_height=2.0)  # fmt: skip
    scene = Scene(camera, [Mesh("Card", Material(surface=card), mesh=mesh)],
                  environment=Environment(colour=(0.0, 0.0, 1.0)))  # fmt: skip
    out = render(scene, RenderSettings(32, 32, pixel_samples=1)).image
    red = out[..., 0] > 0.5
    blue = out[..., 2] > 0.5
    assert np.all(red != blue)  # each pixel wholly card or wholly World
    # the image's row 0 is its top, as the picture's
    np.testing.assert_array_equal(red, np.kron(mask, np.ones((4, 4), bool)))


def _computed(value):
    """`value` as a node computes it (a step of the program before its reader's): a number
    plus 0, a colour mixed with factor 0, both exact."""
    if np.ndim(value) == 0:
        return Link(_node("math", A=value, B=0.0), "Value")
    return Link(_node("mix_color", Fac=0.0, A=value, B=(0.0, 0.0, 0.0)), "Color")


# The nodes whose step goes on in a second row (OP_MORE), with values for the inputs read
# from that row (the rest at their defaults)
CONTINUED = {
    "principled": {"Transmission": 0.2, "Emission Color": (0.6, 0.3, 0.1),
                   "Emission Strength": 1.5, "Specular": 0.8, "Specular Tint": (0.9, 0.7, 0.5)},
    "brick": {"Mortar Size": 0.05, "Mortar Smooth": 0.3, "Bias": 0.2, "Brick Width": 0.4,
              "Row Height": 0.3},
    "noise": {"Distortion": 0.7},
    "voronoi": {"Lacunarity": 2.5, "Randomness": 0.6, "Exponent": 0.7},
}  # fmt: skip


@pytest.mark.parametrize("kind", CONTINUED)
def test_an_input_a_node_computes_renders_as_the_same_value_given(kind):
    """Every input, given as a value or computed by a linked node, renders the same picture.
    A linked input adds steps to the program: they once came between a step and its second
    row, which the step then missed, drawing nothing (an image in a Principled BSDF's
    Emission Color, as Blender's glTF importer links emissive maps, was black)."""
    values = CONTINUED[kind]

    def material(inputs):
        node = ShaderNode(kind, inputs)
        if kind == "principled":
            return Material(surface=node)
        output = "Distance" if kind == "voronoi" else "Color"
        return _diffuse(Link(node, output))

    given, _, _ = _image(material=material(dict(values)))
    computed, _, _ = _image(material=material({k: _computed(v) for k, v in values.items()}))
    plain, _, _ = _image(material=material({}))
    assert not np.array_equal(given, plain)  # the premise: the values change the picture
    np.testing.assert_array_equal(computed, given)


def test_an_image_in_a_principled_emission_is_seen_as_its_pixels_times_the_strength():
    """A Principled BSDF with a black base (no specular) emitting an image, in the dark: what
    the camera sees is the image's pixels times Emission Strength, as the Emission BSDF
    of that image shows them."""
    texture = Texture(pixels=_stripes(), srgb=False)
    image = ShaderNode("image", settings={"texture": texture})
    principled = _node("principled", Base_Color=(0.0, 0.0, 0.0), Specular=0.0,
                       Emission_Color=Link(image, "Color"), Emission_Strength=2.0)  # fmt: skip
    emission = _node("emission", Color=Link(image, "Color"), Strength=2.0)
    seen, _, _ = _image(material=Material(surface=principled), environment_colour=0.0)
    expected, _, _ = _image(material=Material(surface=emission), environment_colour=0.0)
    _, inside = hits(SIZE)
    assert seen[inside].min() > 0.0  # never black where the image is not
    np.testing.assert_allclose(seen, expected, atol=1e-12)
