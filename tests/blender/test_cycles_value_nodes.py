"""Every Mix Color blend and every Vector Math operation, side by side with Cycles
(tests/support/cycles.py), in every Blender version the tests run: a grid of glowing tiles
seen from above, one per blend or operation, each an Emission whose colour (or strength)
is the node's output on the tile's Object coordinates and an image, so that each pixel
shows the node's value itself. One picture holds them all: two renders, not one pair per
node.

Before issue 61 the blends Burn, Dodge, Hue, Saturation, Value, Color, Soft Light and Linear
Light, and the Vector Math node, were named in a warning and drawn as Mix and as their first
input's value."""

import math

import numpy as np
import pytest

from tests.blender.test_cycles_textures import _float_image
from tests.support.cycles import new_scene, side_by_side

pytestmark = pytest.mark.bpy

BLENDS = ("MIX", "ADD", "MULTIPLY", "SUBTRACT", "SCREEN", "DIVIDE", "DIFFERENCE", "DARKEN",
          "LIGHTEN", "OVERLAY", "EXCLUSION", "BURN", "DODGE", "HUE", "SATURATION", "VALUE",
          "COLOR", "SOFT_LIGHT", "LINEAR_LIGHT")  # fmt: skip
VECTOR_OPERATIONS = ("ADD", "SUBTRACT", "MULTIPLY", "DIVIDE", "MULTIPLY_ADD", "CROSS_PRODUCT",
                     "PROJECT", "REFLECT", "REFRACT", "FACEFORWARD", "DOT_PRODUCT", "DISTANCE",
                     "LENGTH", "SCALE", "NORMALIZE", "ABSOLUTE", "POWER", "SIGN", "MINIMUM",
                     "MAXIMUM", "FLOOR", "CEIL", "FRACTION", "MODULO", "WRAP", "SNAP", "SINE",
                     "COSINE", "TANGENT")  # fmt: skip
VALUE_OPERATIONS = ("DOT_PRODUCT", "DISTANCE", "LENGTH")
TILE = 16  # pixels across a tile
COLUMNS = 8
# A pixel agrees when within this of Cycles' (Cycles computes in float32)
CLOSE = 2e-3
# Pixels allowed to differ in a tile: where a step (Floor, Snap, Sign...) or a texel edge
# passes through a pixel's centre, Cycles' 0.01 px spread averages both sides
EDGE_SHARE = 0.05


def _known(node_type, prop, names):
    """Those of `names` this Blender's node type has for `prop` (3.4 lacks Exclusion and
    Vector Math's Power and Sign)."""
    import bpy

    items = getattr(bpy.types, node_type).bl_rna.properties[prop].enum_items
    known = {item.identifier for item in items}
    return [name for name in names if name in known]


def _tile(bpy, scene, k, name):
    """Tile k of the grid: a 1.8-unit square plane of its own, centred on its cell (its
    Object coordinates -0.9..0.9), UVs 0..1, with a new empty node material."""
    rows = math.ceil(len(scene["tiles"]) / COLUMNS)
    x = (k % COLUMNS - (COLUMNS - 1) / 2) * 2.0
    y = ((rows - 1) / 2 - k // COLUMNS) * 2.0
    mesh = bpy.data.meshes.new(name)
    h = 0.9
    mesh.from_pydata([(-h, -h, 0), (h, -h, 0), (h, h, 0), (-h, h, 0)], [], [(0, 1, 2, 3)])
    layer = mesh.uv_layers.new(name="UVMap")
    for corner, uv in zip(layer.data, ((0, 0), (1, 0), (1, 1), (0, 1)), strict=True):
        corner.uv = uv
    material = bpy.data.materials.new(name)
    material.use_nodes = True
    material.node_tree.nodes.clear()
    mesh.materials.append(material)
    obj = bpy.data.objects.new(name, mesh)
    obj.location = (x, y, 0.0)
    scene.collection.objects.link(obj)
    return material.node_tree


def _glow(tree, socket, role="Color"):
    emission = tree.nodes.new("ShaderNodeEmission")
    output = tree.nodes.new("ShaderNodeOutputMaterial")
    tree.links.new(socket, emission.inputs[role])
    tree.links.new(emission.outputs[0], output.inputs[0])


def _blend(bpy, tree, blend):
    """An image's colours mixed at 0.7 with a checker's two saturated, bright colours (Linear
    Light's 2B - 1 stays positive; the HSV blends have a hue to take)."""
    image = tree.nodes.new("ShaderNodeTexImage")
    image.image = bpy.data.images.get("Random") or _float_image(bpy, "Random", 5, 3, seed=1)
    image.interpolation = "Closest"
    checker = tree.nodes.new("ShaderNodeTexChecker")
    checker.inputs["Scale"].default_value = 3.0
    checker.inputs["Color1"].default_value = (0.9, 0.6, 0.7, 1.0)
    checker.inputs["Color2"].default_value = (0.55, 0.95, 0.6, 1.0)
    mix = tree.nodes.new("ShaderNodeMixRGB")
    mix.blend_type = blend
    mix.inputs["Fac"].default_value = 0.7
    tree.links.new(image.outputs["Color"], mix.inputs["Color1"])
    tree.links.new(checker.outputs["Color"], mix.inputs["Color2"])
    # through Absolute: Cycles glows with a negative colour (Subtract's), Whitted with none
    absolute = tree.nodes.new("ShaderNodeVectorMath")
    absolute.operation = "ABSOLUTE"
    tree.links.new(mix.outputs["Color"], absolute.inputs[0])
    _glow(tree, absolute.outputs["Vector"])


def _vector_math(bpy, tree, operation):
    """The operation on the tile's Object coordinates (A) and constants B, C and Scale; its
    vector through Absolute as the colour, or its value through Absolute as the strength."""
    coords = tree.nodes.new("ShaderNodeTexCoord")
    node = tree.nodes.new("ShaderNodeVectorMath")
    node.operation = operation
    tree.links.new(coords.outputs["Object"], node.inputs[0])
    node.inputs[1].default_value = (0.3, -0.5, 0.8)
    node.inputs[2].default_value = (0.2, 0.1, -0.4)
    node.inputs[3].default_value = 0.75  # Scale
    if operation in VALUE_OPERATIONS:
        absolute = tree.nodes.new("ShaderNodeMath")
        absolute.operation = "ABSOLUTE"
        tree.links.new(node.outputs["Value"], absolute.inputs[0])
        _glow(tree, absolute.outputs[0], "Strength")
    else:
        absolute = tree.nodes.new("ShaderNodeVectorMath")
        absolute.operation = "ABSOLUTE"
        tree.links.new(node.outputs["Vector"], absolute.inputs[0])
        _glow(tree, absolute.outputs["Vector"])


def _grid(bpy, tiles):
    """A scene of the tiles, each made by its (name, build(bpy, tree)), seen from above."""
    scene = new_scene(bpy)
    bpy.data.objects.remove(bpy.data.objects["Plane"])
    scene["tiles"] = [name for name, _ in tiles]
    for k, (name, build) in enumerate(tiles):
        build(bpy, _tile(bpy, scene, k, name))
    rows = math.ceil(len(tiles) / COLUMNS)
    scene.render.resolution_x, scene.render.resolution_y = COLUMNS * TILE, rows * TILE
    scene.camera.data.ortho_scale = 2.0 * COLUMNS
    return scene


def _tiles_off(cycles, whitted, names):
    """{name: share of the tile's pixels off by more than CLOSE} (its inner 12 x 12: the
    tile's edge, 0.1 unit, is background)."""
    off = np.abs(whitted - cycles).max(axis=-1) > CLOSE
    shares = {}
    for k, name in enumerate(names):
        row, column = divmod(k, COLUMNS)
        inner = off[
            row * TILE + 2 : (row + 1) * TILE - 2, column * TILE + 2 : (column + 1) * TILE - 2
        ]
        shares[name] = float(inner.mean())
    return shares


def _assert_tiles_agree(bpy, tmp_path, tiles):
    scene = _grid(bpy, tiles)
    cycles, whitted = side_by_side(bpy, scene, tmp_path, samples=16)
    shares = _tiles_off(cycles, whitted, [name for name, _ in tiles])
    print({name: round(share, 3) for name, share in shares.items() if share > 0.0})
    assert cycles.max() > 0.1  # the tiles glow
    wrong = {name: share for name, share in shares.items() if share > EDGE_SHARE}
    assert not wrong, wrong


def test_every_mix_blend_gives_cycles_pixels(bpy_with_whitted, tmp_path):
    blends = _known("ShaderNodeMixRGB", "blend_type", BLENDS)
    tiles = [(blend, lambda bpy, tree, b=blend: _blend(bpy, tree, b)) for blend in blends]
    _assert_tiles_agree(bpy_with_whitted, tmp_path, tiles)


def test_every_vector_math_operation_gives_cycles_pixels(bpy_with_whitted, tmp_path):
    bpy = bpy_with_whitted
    operations = _known("ShaderNodeVectorMath", "operation", VECTOR_OPERATIONS)
    tiles = [(op, lambda bpy, tree, o=op: _vector_math(bpy, tree, o)) for op in operations]
    _assert_tiles_agree(bpy, tmp_path, tiles)


def _curves(extend):
    """An image's colours scaled by 1.6 (past the curves' 0..1: extended) through RGB
    Curves whose combined C curve and red curve each gain a point, at factor 0.8."""

    def build(bpy, tree):
        image = tree.nodes.new("ShaderNodeTexImage")
        image.image = bpy.data.images.get("Random") or _float_image(bpy, "Random", 5, 3, seed=1)
        image.interpolation = "Closest"
        brighter = tree.nodes.new("ShaderNodeVectorMath")
        brighter.operation = "SCALE"
        brighter.inputs["Scale"].default_value = 1.6
        tree.links.new(image.outputs["Color"], brighter.inputs[0])
        curves = tree.nodes.new("ShaderNodeRGBCurve")
        mapping = curves.mapping
        mapping.curves[3].points.new(0.3, 0.6)  # C, applied first
        mapping.curves[0].points.new(0.5, 0.2)  # R
        mapping.extend = extend
        mapping.update()
        curves.inputs["Fac"].default_value = 0.8
        tree.links.new(brighter.outputs["Vector"], curves.inputs["Color"])
        _glow(tree, curves.outputs["Color"])

    return build


def test_rgb_curves_give_cycles_pixels(bpy_with_whitted, tmp_path):
    tiles = [(f"curves_{extend.lower()}", _curves(extend))
             for extend in ("EXTRAPOLATED", "HORIZONTAL")]  # fmt: skip
    _assert_tiles_agree(bpy_with_whitted, tmp_path, tiles)


def _magic(depth, distortion):
    """A Magic texture on the tile's Object coordinates, its colour (or, at depth 0, its
    factor as the strength)."""

    def build(bpy, tree):
        coords = tree.nodes.new("ShaderNodeTexCoord")
        magic = tree.nodes.new("ShaderNodeTexMagic")
        magic.turbulence_depth = depth
        magic.inputs["Scale"].default_value = 1.7
        magic.inputs["Distortion"].default_value = distortion
        tree.links.new(coords.outputs["Object"], magic.inputs["Vector"])
        if depth == 0:
            _glow(tree, magic.outputs["Fac"], "Strength")
        else:
            _glow(tree, magic.outputs["Color"])

    return build


def test_magic_textures_give_cycles_pixels(bpy_with_whitted, tmp_path):
    shapes = ((0, 1.0), (2, 1.0), (5, 1.5), (10, 0.7), (3, 0.0))  # (Depth, Distortion)
    tiles = [
        (f"magic_{depth}_{distortion}", _magic(depth, distortion)) for depth, distortion in shapes
    ]
    _assert_tiles_agree(bpy_with_whitted, tmp_path, tiles)


def _wave(kind, direction, profile, distortion):
    """A Wave texture on the tile's Object coordinates, its factor as the strength."""

    def build(bpy, tree):
        coords = tree.nodes.new("ShaderNodeTexCoord")
        wave = tree.nodes.new("ShaderNodeTexWave")
        wave.wave_type = kind
        if kind == "BANDS":
            wave.bands_direction = direction
        else:
            wave.rings_direction = direction
        wave.wave_profile = profile
        wave.inputs["Scale"].default_value = 0.4
        wave.inputs["Distortion"].default_value = distortion
        wave.inputs["Detail"].default_value = 2.5
        if "Phase Offset" in wave.inputs:
            wave.inputs["Phase Offset"].default_value = 0.7
        tree.links.new(coords.outputs["Object"], wave.inputs["Vector"])
        _glow(tree, wave.outputs["Fac"], "Strength")

    return build


WAVES = (("BANDS", "X", "SIN", 0.0), ("BANDS", "DIAGONAL", "SAW", 0.0),
         ("BANDS", "Y", "TRI", 3.0), ("RINGS", "SPHERICAL", "SIN", 0.0),
         ("RINGS", "Z", "SAW", 2.0), ("RINGS", "X", "TRI", 0.0))  # fmt: skip


def test_wave_textures_give_cycles_pixels(bpy_with_whitted, tmp_path):
    tiles = [("_".join(map(str, shape)).lower(), _wave(*shape)) for shape in WAVES]
    _assert_tiles_agree(bpy_with_whitted, tmp_path, tiles)


def _white_noise(dimensions, output):
    """White Noise of whole-number cells: the tile's Object coordinates times 3, floored
    (the same float32 numbers in both renderers), W their x plus 0.5."""

    def build(bpy, tree):
        coords = tree.nodes.new("ShaderNodeTexCoord")
        cells = tree.nodes.new("ShaderNodeVectorMath")
        cells.operation = "SCALE"
        cells.inputs[3].default_value = 3.0
        tree.links.new(coords.outputs["Object"], cells.inputs[0])
        floor = tree.nodes.new("ShaderNodeVectorMath")
        floor.operation = "FLOOR"
        tree.links.new(cells.outputs["Vector"], floor.inputs[0])
        x = tree.nodes.new("ShaderNodeSeparateXYZ")
        tree.links.new(floor.outputs["Vector"], x.inputs[0])
        w = tree.nodes.new("ShaderNodeMath")
        w.inputs[1].default_value = 0.5
        tree.links.new(x.outputs["X"], w.inputs[0])
        noise = tree.nodes.new("ShaderNodeTexWhiteNoise")
        noise.noise_dimensions = dimensions
        if dimensions != "1D":  # (5.0 hides the inputs a dimension leaves out)
            tree.links.new(floor.outputs["Vector"], noise.inputs["Vector"])
        if dimensions in ("1D", "4D"):
            tree.links.new(w.outputs["Value"], noise.inputs["W"])
        _glow(tree, noise.outputs[output], "Strength" if output == "Value" else "Color")

    return build


def test_white_noise_of_whole_cells_gives_cycles_pixels(bpy_with_whitted, tmp_path):
    tiles = [(f"white_noise_{d}_{output}", _white_noise(d, output))
             for d in ("1D", "2D", "3D", "4D") for output in ("Value", "Color")]  # fmt: skip
    _assert_tiles_agree(bpy_with_whitted, tmp_path, tiles)
