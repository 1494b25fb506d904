"""Shader graphs (core.model.shader) into the flat programs core.kernels.shader_program runs.

The graph is walked from the material's surface node down. Each value a node computes gets a
triple of stack slots (a plain number sits in the first), each constant input a triple in the
constants block the program starts from; node outputs are computed once however many inputs
they feed. Closure nodes become steps that add lobes times a weight slot; a Mix Shader splits
its weight. Colours used as numbers become their luminance, vectors their mean, and numbers
used as triples are repeated, as in Blender.

A program that reads nothing of the hit (no texture coordinate, no image) is `constant`: the
compile runs it once and stores what it makes in the material table.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ..kernels import shader_program as sp
from ..kernels.facing_values import FACING_FRESNEL, FACING_LAYER_FACING, FACING_LAYER_FRESNEL
from ..model.shader import (
    DISTRIBUTIONS,
    EDGE_ATTRIBUTE,
    EXTENSIONS,
    GRADIENT_TYPES,
    MAPPING_TYPES,
    MATH_OPERATIONS,
    MIX_BLENDS,
    NORMAL_MAP_MIXES,
    NORMAL_MAP_SPACES,
    RAMP_INTERPOLATIONS,
    SHADER_NODES,
    TANGENT_ATTRIBUTE,
    VECTOR_MATH_OPERATIONS,
    VORONOI_FEATURES,
    VORONOI_HASHES,
    VORONOI_METRICS,
    WAVE_BANDS,
    WAVE_PROFILES,
    WAVE_RINGS,
    WAVE_TYPES,
    Link,
    coated,
)

COORDS = {"UV": sp.COORD_UV, "Generated": sp.COORD_GENERATED, "Object": sp.COORD_OBJECT,
          "Normal": sp.COORD_NORMAL}  # fmt: skip
# Light Path's outputs: the entry of the kernels' `ray` each reads (core.kernels.shader_program)
RAY_COORDS = {
    name: sp.COORD_IS_CAMERA + entry
    for name, entry in (
        ("Is Camera Ray", sp.RAY_IS_CAMERA),
        ("Is Shadow Ray", sp.RAY_IS_SHADOW),
        ("Is Diffuse Ray", sp.RAY_NEVER),
        ("Is Glossy Ray", sp.RAY_IS_GLOSSY),
        ("Is Reflection Ray", sp.RAY_IS_REFLECTION),
        ("Is Transmission Ray", sp.RAY_IS_TRANSMISSION),
        ("Ray Length", sp.RAY_LENGTH),
        ("Ray Depth", sp.RAY_DEPTH),
        ("Diffuse Depth", sp.RAY_NEVER),
        ("Glossy Depth", sp.RAY_GLOSSY_DEPTH),
        ("Transparent Depth", sp.RAY_TRANSPARENT_DEPTH),
        ("Transmission Depth", sp.RAY_TRANSMISSION_DEPTH),
    )
}
GEOMETRY_COORDS = {
    "Position": sp.COORD_POSITION,
    "Normal": sp.COORD_GEOMETRY_NORMAL,
    "True Normal": sp.COORD_TRUE_NORMAL,
    "Incoming": sp.COORD_INCOMING,
    "Backfacing": sp.COORD_IS_CAMERA + sp.RAY_BACKFACING,
}
FACING_OUTPUTS = {
    "fresnel": {"Fac": FACING_FRESNEL},
    "layer_weight": {"Fresnel": FACING_LAYER_FRESNEL, "Facing": FACING_LAYER_FACING},
}
# Outputs that are colours (as numbers: their luminance) rather than vectors (their mean)
COLOUR_OUTPUTS = {"Color"}


@dataclass
class Program:
    ops: list = field(default_factory=list)  # rows of 8 ints; operands as ("c"|"v", index)
    constants: list = field(default_factory=list)
    values: int = 0  # computed slots used
    varying: bool = False  # reads the hit (coordinates, images)
    needs_frame: bool = False  # reads the surface's tangents or steps across it
    attributes: int = 0  # how many colour attributes its caller puts on the stack (0: none)
    textures: list = field(default_factory=list)  # core Textures the image steps read

    def constant(self, value) -> tuple:
        v = np.asarray(value, float).ravel()
        triple = np.repeat(v[:1], 3) if v.size == 1 else v[:3]
        self.constants.extend(float(x) for x in triple)
        return ("c", len(self.constants) - 3)

    def slot(self) -> tuple:
        self.values += 3
        return ("v", self.values - 3)

    def step(self, *row) -> None:
        assert len(row) <= 8, row  # op and seven operands
        self.ops.append(list(row) + [0] * (8 - len(row)))

    def step_with_more(self, row: tuple, more: tuple) -> None:
        """A step whose operands go on in the next row (OP_MORE), which the kernel reads
        as that row. Both rows' operands are evaluated by the caller first, since an input
        linked to a texture adds steps of its own: made between the two rows, they took the
        continuation's place, and the step drew nothing (an image in a Principled BSDF's
        Emission Color, as Blender's glTF importer links every emissive map, went black)."""
        self.step(*row)
        self.step(sp.OP_MORE, *more)

    def resolved(self) -> tuple[np.ndarray, np.ndarray]:
        """(ops int32 (n, 8), constants float64): operands as stack slots, the constants
        first and the computed values after them."""
        base = len(self.constants)
        rows = []
        for row in self.ops:
            rows.append([_slot(x, base) for x in row])
        ops = np.array(rows, np.int32).reshape(-1, 8)
        return ops, np.array(self.constants, float)


def _slot(operand, base):
    if isinstance(operand, tuple):
        kind, index = operand
        return index if kind == "c" else base + index
    return int(operand)


def _distribution(node) -> int:
    """A rough closure's microfacet distribution, as core.kernels.microfacet numbers it."""
    return DISTRIBUTIONS.index(node.setting("distribution"))


def _outputs_read(surface) -> set:
    """(id(node), output) of every output a link of the graph reads."""
    read, seen, stack = set(), set(), [surface]
    while stack:
        node = stack.pop()
        if id(node) in seen:
            continue
        seen.add(id(node))
        for given in node.inputs.values():
            if isinstance(given, Link):
                read.add((id(given.node), given.output))
                stack.append(given.node)
    return read


class ProgramBuilder:
    """Builds one material's program; `texture_row(texture)` gives the row of a core
    Texture in the material table's textures."""

    def __init__(self, texture_row, attribute_names=()):
        self.program = Program()
        self.texture_row = texture_row
        # the scene's colour attribute names (core.model.shader.attribute_names): their
        # numbers on the stack
        self.attribute_names = list(attribute_names)
        self.outputs: dict = {}  # (id(node), output, where) -> (operand, shape)
        # where the values are wanted: 0 the hit, 1 and 2 a step across (a Bump's heights)
        self.where = 0
        self.used: set = set()  # (id(node), output) of every output something reads

    def build(self, surface) -> Program:
        self.used = _outputs_read(surface)
        weight = self.program.constant(1.0)
        self.shader(surface, weight)
        return self.program

    # shaders

    def shader(self, node, weight) -> None:
        kind = node.kind
        p = self.program
        if kind in ("mix_shader", "add_shader"):
            a, b = node.input("Shader A"), node.input("Shader B")
            if kind == "add_shader":
                for linked in (a, b):
                    if isinstance(linked, Link):
                        self.shader(linked.node, weight)
                return
            fac = self.value(node.input("Fac"), "value")
            weight_a, weight_b = p.slot(), p.slot()
            p.step(sp.OP_SPLIT, weight_a, weight_b, weight, fac)
            for linked, share in ((a, weight_a), (b, weight_b)):
                if isinstance(linked, Link):
                    self.shader(linked.node, share)
            return
        v = self.value
        if kind == "diffuse":
            p.step(sp.OP_DIFFUSE, weight, v(node.input("Color"), "triple"),
                   v(node.input("Roughness"), "value"), 0, 0, 0, self._normal(node))  # fmt: skip
        elif kind == "translucent":
            p.step(sp.OP_TRANSLUCENT, weight, v(node.input("Color"), "triple"), 0, 0, 0, 0,
                   self._normal(node))  # fmt: skip
        elif kind == "glossy":
            p.step(sp.OP_GLOSSY, weight, v(node.input("Color"), "triple"),
                   v(node.input("Roughness"), "value"), _distribution(node), 0, 0,
                   self._normal(node))  # fmt: skip
        elif kind == "metallic":
            p.step(sp.OP_METALLIC, weight, v(node.input("Base Color"), "triple"),
                   v(node.input("Edge Tint"), "triple"), v(node.input("Roughness"), "value"),
                   _distribution(node), 0, self._normal(node))  # fmt: skip
        elif kind in ("glass", "refraction"):
            p.step(sp.OP_GLASS, weight, v(node.input("Color"), "triple"),
                   v(node.input("IOR"), "value"), int(kind == "glass"),
                   v(node.input("Roughness"), "value"), _distribution(node),
                   self._normal(node))  # fmt: skip
        elif kind == "transparent":
            p.step(sp.OP_TRANSPARENT, weight, self.value(node.input("Color"), "triple"))
        elif kind == "emission":
            p.step(sp.OP_EMISSION, weight, self.value(node.input("Color"), "triple"),
                   self.value(node.input("Strength"), "value"))  # fmt: skip
        elif kind == "holdout":
            p.step(sp.OP_HOLDOUT, weight)
        elif kind == "principled":
            row = (sp.OP_PRINCIPLED, weight, v(node.input("Base Color"), "triple"),
                   v(node.input("Metallic"), "value"), v(node.input("Roughness"), "value"),
                   v(node.input("IOR"), "value"), v(node.input("Alpha"), "value"),
                   self._normal(node))  # fmt: skip
            more = (v(node.input("Transmission"), "value"),
                    v(node.input("Emission Color"), "triple"),
                    v(node.input("Emission Strength"), "value"), v(node.input("Specular"), "value"),
                    v(node.input("Specular Tint"), "triple"),
                    int(bool(node.setting("layered"))), _distribution(node))  # fmt: skip
            p.step_with_more(row, more)
            p.step(sp.OP_DIFFUSE_ROUGHNESS, weight, v(node.input("Diffuse Roughness"), "value"))
            if coated(node):
                coat_normal = node.input("Coat Normal")
                op = sp.OP_CLEAR_COAT if node.setting("coat_albedo") == "LOBE" \
                    else sp.OP_CLEAR_COAT_AT_NORMAL  # fmt: skip
                p.step(op, weight, v(node.input("Coat Weight"), "value"),
                       v(node.input("Coat Roughness"), "value"),
                       v(node.input("Coat IOR"), "value"), v(node.input("Coat Tint"), "triple"),
                       v(node.input("Alpha"), "value"),
                       self.value(coat_normal, "triple") if isinstance(coat_normal, Link)
                       else -1)  # fmt: skip

    def _normal(self, node):
        """The operand of a closure's Normal input, or -1 (the surface's own normal)."""
        given = node.input("Normal")
        if not isinstance(given, Link):
            return -1
        return self.value(given, "triple")

    # values

    def value(self, given, want: str, default_coord: int = sp.COORD_UV):
        """The operand of an input: its constant, or what its link computes, converted to
        `want` ("value" or "triple")."""
        if given is None:  # a texture's own coordinates
            return self._coord(default_coord)
        if not isinstance(given, Link):
            return self.program.constant(given)
        operand, shape = self._output(given.node, given.output)
        if want == shape:
            return operand
        out = self.program.slot()
        if want == "triple":  # a number used as a colour or vector: repeated
            self.program.step(sp.OP_COMBINE, out, operand, operand, operand)
        elif given.output in COLOUR_OUTPUTS:
            self.program.step(sp.OP_TO_VALUE, out, operand)
        else:
            self.program.step(sp.OP_AVERAGE, out, operand)
        return out

    def _coord(self, which: int):
        key = ("coord", which, self.where)
        if key not in self.outputs:
            out = self.program.slot()
            self.program.step(sp.OP_COORD, out, which, self.where)
            self.program.varying = True
            self.outputs[key] = (out, "triple")
        return self.outputs[key][0]

    def _output(self, node, output: str):
        key = (id(node), output, self.where)
        if key not in self.outputs:
            self._emit(node)
        return self.outputs[key]

    def _emit(self, node) -> None:
        """The steps computing every output of `node`, stored in self.outputs."""
        p, v, kind = self.program, self.value, node.kind
        outputs = SHADER_NODES[kind]["outputs"]
        slots = {name: p.slot() for name in outputs}
        for name, shape in outputs.items():
            self.outputs[(id(node), name, self.where)] = (slots[name], shape)
        if kind == "tex_coord":
            for name, which in COORDS.items():
                p.step(sp.OP_COORD, slots[name], which, self.where)
            p.varying = True
        elif kind == "attribute":
            k = self.attribute_names.index(node.setting("name"))
            p.step(sp.OP_ATTRIBUTE, slots["Color"], slots["Alpha"], sp.attribute_slot(k))
            p.step(sp.OP_COPY, slots["Vector"], slots["Color"])
            p.step(sp.OP_AVERAGE, slots["Fac"], slots["Color"])
            p.varying = True
            p.attributes = len(self.attribute_names)
        elif kind == "geometry":
            for name, which in GEOMETRY_COORDS.items():
                p.step(sp.OP_COORD, slots[name], which, self.where)
            p.varying = True
        elif kind == "light_path":
            for name, which in RAY_COORDS.items():
                p.step(sp.OP_COORD, slots[name], which, self.where)
            p.varying = True
        elif kind in ("fresnel", "layer_weight"):
            value = v(node.input("IOR" if kind == "fresnel" else "Blend"), "value")
            normal = self._normal(node)
            for name, which in FACING_OUTPUTS[kind].items():
                p.step(sp.OP_FACING, slots[name], value, normal, which)
            p.varying = True
        elif kind == "bump":
            heights = []
            for where in (0, 1, 2):  # the height here, and a step along u and along v
                outer, self.where = self.where, where
                heights.append(v(node.input("Height"), "value"))
                self.where = outer
            strength, distance = (
                v(node.input("Strength"), "value"),
                v(node.input("Distance"), "value"),
            )
            invert = int(bool(node.setting("invert")))
            p.step(sp.OP_BUMP, slots["Normal"], *heights, strength, distance, invert)
            p.varying = p.needs_frame = True
        elif kind == "normal_map":
            tangents = -1  # the mesh's MikkTSpace tangents, read as an attribute
            if node.setting("space") == "TANGENT":
                tangents = sp.attribute_slot(self.attribute_names.index(TANGENT_ATTRIBUTE))
                p.attributes = len(self.attribute_names)
            p.step(sp.OP_NORMAL_MAP, slots["Normal"], v(node.input("Color"), "triple"),
                   v(node.input("Strength"), "value"),
                   NORMAL_MAP_SPACES.index(node.setting("space")), tangents,
                   NORMAL_MAP_MIXES.index(node.setting("strength_mix")))  # fmt: skip
            p.varying = p.needs_frame = True
        elif kind == "mapping":
            p.step(sp.OP_MAPPING, slots["Vector"], v(node.input("Vector"), "triple"),
                   v(node.input("Location"), "triple"), v(node.input("Rotation"), "triple"),
                   v(node.input("Scale"), "triple"), 0,
                   MAPPING_TYPES.index(node.setting("type")))  # fmt: skip
        elif kind == "image":
            texture = node.setting("texture")
            interpolation = 1 if node.setting("interpolation") == "Closest" else 0
            p.step(sp.OP_IMAGE, slots["Color"], slots["Alpha"],
                   v(node.input("Vector"), "triple", sp.COORD_UV), self.texture_row(texture),
                   interpolation, EXTENSIONS.index(node.setting("extension")))  # fmt: skip
            p.varying = True
        elif kind == "checker":
            p.step(sp.OP_CHECKER, slots["Color"], slots["Fac"],
                   v(node.input("Vector"), "triple", sp.COORD_GENERATED),
                   v(node.input("Color1"), "triple"), v(node.input("Color2"), "triple"),
                   v(node.input("Scale"), "value"))  # fmt: skip
        elif kind == "brick":
            row = (sp.OP_BRICK, slots["Color"], slots["Fac"],
                   v(node.input("Vector"), "triple", sp.COORD_GENERATED),
                   v(node.input("Color1"), "triple"), v(node.input("Color2"), "triple"),
                   v(node.input("Mortar"), "triple"), v(node.input("Scale"), "value"))  # fmt: skip
            shape = (float(node.setting("offset")), float(node.setting("squash")), 0.0)
            frequencies = node.setting("offset_frequency") * 256 + node.setting("squash_frequency")
            more = (v(node.input("Mortar Size"), "value"),
                    v(node.input("Mortar Smooth"), "value"), v(node.input("Bias"), "value"),
                    v(node.input("Brick Width"), "value"), v(node.input("Row Height"), "value"),
                    p.constant(shape), frequencies)  # fmt: skip
            p.step_with_more(row, more)
        elif kind == "noise":
            row = (sp.OP_NOISE, slots["Color"], slots["Fac"],
                   v(node.input("Vector"), "triple", sp.COORD_GENERATED),
                   *(v(node.input(name), "value")
                     for name in ("Scale", "Detail", "Roughness", "Lacunarity")))  # fmt: skip
            # its Color costs two more fractal sums: made only where something reads it
            more = (v(node.input("Distortion"), "value"), int(bool(node.setting("normalize"))),
                    int((id(node), "Color") in self.used))  # fmt: skip
            p.step_with_more(row, more)
        elif kind == "voronoi":
            names = ("Scale", "Detail", "Roughness", "Lacunarity", "Randomness", "Exponent",
                     "Smoothness")  # fmt: skip
            values = [v(node.input(name), "value") for name in names]
            row = (sp.OP_VORONOI, slots["Color"], slots["Distance"], slots["Position"],
                   v(node.input("Vector"), "triple", sp.COORD_GENERATED), *values[:3])  # fmt: skip
            modes = (VORONOI_FEATURES.index(node.setting("feature"))
                     + 4 * VORONOI_METRICS.index(node.setting("distance"))
                     + 16 * int(bool(node.setting("normalize")))
                     + 32 * VORONOI_HASHES.index(node.setting("cell_hash")))  # fmt: skip
            p.step_with_more(row, (*values[3:6], modes, values[6]))
        elif kind == "wave":
            row = (sp.OP_WAVE, slots["Color"], slots["Fac"],
                   v(node.input("Vector"), "triple", sp.COORD_GENERATED),
                   *(v(node.input(name), "value")
                     for name in ("Scale", "Distortion", "Detail")))  # fmt: skip
            modes = (WAVE_TYPES.index(node.setting("type"))
                     + 2 * WAVE_BANDS.index(node.setting("bands_direction"))
                     + 8 * WAVE_RINGS.index(node.setting("rings_direction"))
                     + 32 * WAVE_PROFILES.index(node.setting("profile")))  # fmt: skip
            names = ("Detail Scale", "Detail Roughness", "Phase Offset")
            more = (*(v(node.input(name), "value") for name in names), modes)
            p.step_with_more(row, more)
        elif kind == "white_noise":
            p.step(sp.OP_WHITE_NOISE, slots["Color"], slots["Value"],
                   v(node.input("Vector"), "triple", sp.COORD_GENERATED),
                   v(node.input("W"), "value"), int(node.setting("dimensions")))  # fmt: skip
        elif kind == "magic":
            p.step(sp.OP_MAGIC, slots["Color"], slots["Fac"],
                   v(node.input("Vector"), "triple", sp.COORD_GENERATED),
                   v(node.input("Scale"), "value"), v(node.input("Distortion"), "value"),
                   int(node.setting("depth")))  # fmt: skip
        elif kind == "gradient":
            p.step(sp.OP_GRADIENT, slots["Color"], slots["Fac"],
                   v(node.input("Vector"), "triple", sp.COORD_GENERATED),
                   GRADIENT_TYPES.index(node.setting("type")))  # fmt: skip
        elif kind == "math":
            p.step(sp.OP_MATH, slots["Value"], v(node.input("A"), "value"),
                   v(node.input("B"), "value"), v(node.input("C"), "value"),
                   MATH_OPERATIONS.index(node.setting("operation")),
                   int(bool(node.setting("clamp"))))  # fmt: skip
        elif kind == "vector_math":
            p.step(sp.OP_VECTOR_MATH, slots["Vector"], slots["Value"],
                   v(node.input("A"), "triple"), v(node.input("B"), "triple"),
                   v(node.input("C"), "triple"), v(node.input("Scale"), "value"),
                   VECTOR_MATH_OPERATIONS.index(node.setting("operation")))  # fmt: skip
        elif kind == "mix_color":
            p.step(sp.OP_MIX, slots["Color"], v(node.input("Fac"), "value"),
                   v(node.input("A"), "triple"), v(node.input("B"), "triple"),
                   MIX_BLENDS.index(node.setting("blend")),
                   int(bool(node.setting("clamp"))))  # fmt: skip
        elif kind == "invert":
            p.step(sp.OP_INVERT, slots["Color"], v(node.input("Fac"), "value"),
                   v(node.input("Color"), "triple"))  # fmt: skip
        elif kind == "gamma":
            p.step(sp.OP_GAMMA, slots["Color"], v(node.input("Color"), "triple"),
                   v(node.input("Gamma"), "value"))  # fmt: skip
        elif kind == "bright_contrast":
            p.step(sp.OP_BRIGHT, slots["Color"], v(node.input("Color"), "triple"),
                   v(node.input("Bright"), "value"),
                   v(node.input("Contrast"), "value"))  # fmt: skip
        elif kind == "hsv":
            p.step(sp.OP_HSV, slots["Color"], v(node.input("Hue"), "value"),
                   v(node.input("Saturation"), "value"), v(node.input("Value"), "value"),
                   v(node.input("Fac"), "value"), v(node.input("Color"), "triple"))  # fmt: skip
        elif kind == "rgb_curves":
            first = len(p.constants)
            p.constants.extend(float(x) for x in node.setting("range"))
            p.constants.append(float(bool(node.setting("extrapolate"))))
            p.constants.extend(float(x) for x in np.ravel(node.setting("table")))
            p.step(sp.OP_CURVES, slots["Color"], v(node.input("Fac"), "value"),
                   v(node.input("Color"), "triple"), ("c", first),
                   len(node.setting("table")))  # fmt: skip
        elif kind == "color_ramp":
            stops = sorted(node.setting("stops"), key=lambda stop: stop[0])
            first = None
            for position, rgba in stops:
                start = len(p.constants)
                p.constants.extend([float(position), *(float(c) for c in rgba)])
                first = start if first is None else first
            p.step(sp.OP_RAMP, slots["Color"], slots["Alpha"], v(node.input("Fac"), "value"),
                   ("c", first), len(stops),
                   RAMP_INTERPOLATIONS.index(node.setting("interpolation")))  # fmt: skip
        elif kind == "separate":
            p.step(sp.OP_SEPARATE, slots["X"], slots["Y"], slots["Z"],
                   v(node.input("Vector"), "triple"))  # fmt: skip
        elif kind == "combine":
            p.step(sp.OP_COMBINE, slots["Vector"], v(node.input("X"), "value"),
                   v(node.input("Y"), "value"), v(node.input("Z"), "value"))  # fmt: skip
        elif kind == "to_bw":
            p.step(sp.OP_TO_VALUE, slots["Val"], v(node.input("Color"), "triple"))
        elif kind == "wireframe":
            edges = sp.attribute_slot(self.attribute_names.index(EDGE_ATTRIBUTE))
            p.step(sp.OP_WIREFRAME, slots["Fac"], v(node.input("Size"), "value"), edges)
            p.varying = True
            p.attributes = len(self.attribute_names)
        elif kind == "blackbody":
            p.step(sp.OP_BLACKBODY, slots["Color"], v(node.input("Temperature"), "value"))
