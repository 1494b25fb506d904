"""Shader graphs: a material as Blender's nodes describe it, without Blender.

A `ShaderNode` is one node: its kind (SHADER_NODES names them, with their inputs, outputs
and settings), its inputs (a constant number or RGB/XYZ triple, or a `Link` to another
node's output) and its settings. A `Material` whose `surface` is a closure node (a BSDF,
Emission, Mix Shader...) renders from the graph below it: `core.compile.shader_program`
turns it into a flat program the kernels run at each hit (`core.kernels.shader_program`),
folded into the material table when nothing in it varies over the surface.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ..errors import SceneError

# Each node kind: its inputs with their defaults (a float, or a triple for colours and
# vectors; None for a vector whose default is a texture coordinate), its outputs (name:
# "value" or "triple"), and whether it is a closure (its output is a shader).
# The vector default `None` means the texture's own default coordinates: UV for images,
# Generated for procedural textures, as in Blender.
RGB = (0.8, 0.8, 0.8)
# Blender's Light Path outputs Whitted evaluates (Is Singular Ray and Is Volume Scatter Ray:
# not; core.compile.shader_program has what each is of a Whitted ray)
LIGHT_PATH_OUTPUTS = (
    "Is Camera Ray",
    "Is Shadow Ray",
    "Is Diffuse Ray",
    "Is Glossy Ray",
    "Is Reflection Ray",
    "Is Transmission Ray",
    "Ray Length",
    "Ray Depth",
    "Diffuse Depth",
    "Glossy Depth",
    "Transparent Depth",
    "Transmission Depth",
)
SHADER_NODES = {
    # closures
    "principled": dict(
        inputs={
            "Base Color": RGB,
            "Metallic": 0.0,
            "Roughness": 0.5,
            "Diffuse Roughness": 0.0,
            "IOR": 1.5,
            "Alpha": 1.0,
            "Transmission": 0.0,
            "Emission Color": (1.0, 1.0, 1.0),
            "Emission Strength": 0.0,
            "Specular": 0.5,
            "Specular Tint": (1.0, 1.0, 1.0),
            "Normal": None,
            # A clear layer over the rest (Blender 4.0 on; core.kernels.clear_coat); its
            # Normal None: the surface's own smooth normal
            "Coat Weight": 0.0,
            "Coat Roughness": 0.03,
            "Coat IOR": 1.5,
            "Coat Tint": (1.0, 1.0, 1.0),
            "Coat Normal": None,
        },
        closure=True,
        # coat_albedo (COAT_ALBEDOS): what dims the layers under a rough coat
        settings={"layered": True, "distribution": "GGX", "coat_albedo": "LOBE"},
    ),  # fmt: skip
    # Roughness: Oren-Nayar's (core.kernels.rough_diffuse), 0 Lambert's
    "diffuse": dict(inputs={"Color": RGB, "Roughness": 0.0, "Normal": None}, closure=True),
    # Lambertian transmission: the light falling on the other side (core.kernels.translucent)
    "translucent": dict(inputs={"Color": RGB, "Normal": None}, closure=True),
    # A rough lobe's microfacet distribution (DISTRIBUTIONS; core.kernels.microfacet)
    "glossy": dict(
        inputs={"Color": RGB, "Roughness": 0.5, "Normal": None},
        closure=True,
        settings={"distribution": "GGX"},
    ),  # fmt: skip
    "metallic": dict(
        inputs={"Base Color": RGB, "Edge Tint": (1.0, 1.0, 1.0), "Roughness": 0.5, "Normal": None},
        closure=True,
        settings={"distribution": "GGX"},
    ),  # fmt: skip
    "glass": dict(
        inputs={"Color": (1.0, 1.0, 1.0), "Roughness": 0.0, "IOR": 1.5, "Normal": None},
        closure=True,
        settings={"distribution": "GGX"},
    ),  # fmt: skip
    "refraction": dict(
        inputs={"Color": (1.0, 1.0, 1.0), "Roughness": 0.0, "IOR": 1.5, "Normal": None},
        closure=True,
        settings={"distribution": "GGX"},
    ),  # fmt: skip
    "transparent": dict(inputs={"Color": (1.0, 1.0, 1.0)}, closure=True),
    "emission": dict(inputs={"Color": (1.0, 1.0, 1.0), "Strength": 1.0}, closure=True),
    "holdout": dict(inputs={}, closure=True),
    "mix_shader": dict(inputs={"Fac": 0.5, "Shader A": None, "Shader B": None}, closure=True),
    "add_shader": dict(inputs={"Shader A": None, "Shader B": None}, closure=True),
    # values
    "tex_coord": dict(
        inputs={},
        outputs={"UV": "triple", "Generated": "triple", "Object": "triple", "Normal": "triple"},
    ),  # fmt: skip
    # Blender's Geometry node: world position, the normals facing the ray, the way back
    # along it, 1 on a surface's back (core.kernels.shader_program.geometry_vector)
    "geometry": dict(
        inputs={},
        outputs={
            "Position": "triple",
            "Normal": "triple",
            "True Normal": "triple",
            "Incoming": "triple",
            "Backfacing": "value",
        },
    ),  # fmt: skip
    # A mesh's colour attribute by name, "" its default one (Blender's Color Attribute and
    # Attribute nodes; core.kernels.attributes): RGB, its mean, alpha; zero where absent
    "attribute": dict(
        inputs={},
        outputs={"Color": "triple", "Vector": "triple", "Fac": "value", "Alpha": "value"},
        settings={"name": ""},
    ),  # fmt: skip
    # What the ray that met the surface is: 1 or 0, and its bounces (Blender's Light Path)
    # What the ray that met the surface is (LIGHT_PATH_OUTPUTS), as Cycles' path flags
    "light_path": dict(inputs={}, outputs=dict.fromkeys(LIGHT_PATH_OUTPUTS, "value")),
    # How squarely the ray meets the surface (Blender's Fresnel and Layer Weight nodes,
    # core.kernels.facing_values); Normal None: the surface's shading normal
    "fresnel": dict(inputs={"IOR": 1.5, "Normal": None}, outputs={"Fac": "value"}),
    "layer_weight": dict(
        inputs={"Blend": 0.5, "Normal": None},
        outputs={"Fresnel": "value", "Facing": "value"},
    ),  # fmt: skip
    "mapping": dict(
        inputs={
            "Vector": (0.0, 0.0, 0.0),
            "Location": (0.0, 0.0, 0.0),
            "Rotation": (0.0, 0.0, 0.0),
            "Scale": (1.0, 1.0, 1.0),
        },
        outputs={"Vector": "triple"},
        settings={"type": "POINT"},
    ),  # fmt: skip
    "image": dict(
        inputs={"Vector": None},
        outputs={"Color": "triple", "Alpha": "value"},
        settings={"texture": None, "interpolation": "Linear", "extension": "REPEAT"},
    ),  # fmt: skip
    "checker": dict(
        inputs={"Vector": None, "Color1": (0.8, 0.8, 0.8), "Color2": (0.2, 0.2, 0.2), "Scale": 5.0},
        outputs={"Color": "triple", "Fac": "value"},
    ),  # fmt: skip
    "brick": dict(
        inputs={
            "Vector": None,
            "Color1": (0.8, 0.8, 0.8),
            "Color2": (0.2, 0.2, 0.2),
            "Mortar": (0.0, 0.0, 0.0),
            "Scale": 5.0,
            "Mortar Size": 0.02,
            "Mortar Smooth": 0.1,
            "Bias": 0.0,
            "Brick Width": 0.5,
            "Row Height": 0.25,
        },
        outputs={"Color": "triple", "Fac": "value"},
        # Blender's Offset (0..1) every Offset Frequency-th row, and Squash: the brick width's
        # factor every Squash Frequency-th row (frequencies 1..99)
        settings={"offset": 0.5, "offset_frequency": 2, "squash": 1.0, "squash_frequency": 2},
    ),  # fmt: skip
    "noise": dict(
        inputs={
            "Vector": None,
            "Scale": 5.0,
            "Detail": 2.0,
            "Roughness": 0.5,
            "Lacunarity": 2.0,
            "Distortion": 0.0,
        },
        outputs={"Fac": "value", "Color": "triple"},
        settings={"normalize": True},  # 3D, fractal Brownian motion (Blender's default)
    ),  # fmt: skip
    "voronoi": dict(
        inputs={
            "Vector": None,
            "Scale": 5.0,
            "Detail": 0.0,
            "Roughness": 0.5,
            "Lacunarity": 2.0,
            "Exponent": 0.5,
            "Randomness": 1.0,
            "Smoothness": 1.0,
        },
        outputs={"Distance": "value", "Color": "triple", "Position": "triple"},
        # 3D; Blender's Feature and Distance; the cell hash of the Blender that made it
        # (core.kernels.voronoi: "LOOKUP3" before 5.0, "PCG" from 5.0)
        settings={"feature": "F1", "distance": "EUCLIDEAN", "normalize": False, "cell_hash": "PCG"},
    ),  # fmt: skip
    "gradient": dict(
        inputs={"Vector": None},
        outputs={"Color": "triple", "Fac": "value"},
        settings={"type": "LINEAR"},
    ),  # fmt: skip
    # Blender's Wave texture (WAVE_TYPES, WAVE_BANDS, WAVE_RINGS, WAVE_PROFILES)
    "wave": dict(
        inputs={
            "Vector": None,
            "Scale": 5.0,
            "Distortion": 0.0,
            "Detail": 2.0,
            "Detail Scale": 1.0,
            "Detail Roughness": 0.5,
            "Phase Offset": 0.0,
        },
        outputs={"Color": "triple", "Fac": "value"},
        settings={
            "type": "BANDS",
            "bands_direction": "X",
            "rings_direction": "X",
            "profile": "SIN",
        },
    ),  # fmt: skip
    # Blender's White Noise texture: `dimensions` 1 (W), 2, 3 (Vector) or 4 (both)
    "white_noise": dict(
        inputs={"Vector": None, "W": 0.0},
        outputs={"Value": "value", "Color": "triple"},
        settings={"dimensions": 3},
    ),  # fmt: skip
    # Blender's Magic texture: `depth` its Depth (0..10)
    "magic": dict(
        inputs={"Vector": None, "Scale": 5.0, "Distortion": 1.0},
        outputs={"Color": "triple", "Fac": "value"},
        settings={"depth": 2},
    ),  # fmt: skip
    "math": dict(
        inputs={"A": 0.5, "B": 0.5, "C": 0.0},
        outputs={"Value": "value"},
        settings={"operation": "ADD", "clamp": False},
    ),  # fmt: skip
    # Blender's Vector Math: A, B, C its three vectors, Scale its number (Scale, Refract)
    "vector_math": dict(
        inputs={"A": (0.0, 0.0, 0.0), "B": (0.0, 0.0, 0.0), "C": (0.0, 0.0, 0.0), "Scale": 1.0},
        outputs={"Vector": "triple", "Value": "value"},
        settings={"operation": "ADD"},
    ),  # fmt: skip
    "mix_color": dict(
        inputs={"Fac": 0.5, "A": (0.5, 0.5, 0.5), "B": (0.5, 0.5, 0.5)},
        outputs={"Color": "triple"},
        settings={"blend": "MIX", "clamp": False},
    ),  # fmt: skip
    "invert": dict(inputs={"Fac": 1.0, "Color": (0.0, 0.0, 0.0)}, outputs={"Color": "triple"}),
    "gamma": dict(inputs={"Color": (1.0, 1.0, 1.0), "Gamma": 1.0}, outputs={"Color": "triple"}),
    "bright_contrast": dict(
        inputs={"Color": (1.0, 1.0, 1.0), "Bright": 0.0, "Contrast": 0.0},
        outputs={"Color": "triple"},
    ),  # fmt: skip
    "hsv": dict(
        inputs={"Hue": 0.5, "Saturation": 1.0, "Value": 1.0, "Fac": 1.0, "Color": (0.8, 0.8, 0.8)},
        outputs={"Color": "triple"},
    ),  # fmt: skip
    # Blender's RGB Curves: `table` its curves sampled as Cycles bakes them (CURVE_TABLE_SIZE
    # RGB rows, each channel's curve after the combined C curve), over x from `range`'s first
    # to its second; beyond it, extended along the end rows' slope (`extrapolate`) or flat
    "rgb_curves": dict(
        inputs={"Fac": 1.0, "Color": (0.5, 0.5, 0.5)},
        outputs={"Color": "triple"},
        settings={"table": None, "range": (0.0, 1.0), "extrapolate": True},
    ),  # fmt: skip
    "color_ramp": dict(
        inputs={"Fac": 0.5},
        outputs={"Color": "triple", "Alpha": "value"},
        settings={
            "stops": ((0.0, (0.0, 0.0, 0.0, 1.0)), (1.0, (1.0,) * 4)),
            "interpolation": "LINEAR",
        },
    ),  # fmt: skip
    "separate": dict(
        inputs={"Vector": (0.0, 0.0, 0.0)}, outputs={"X": "value", "Y": "value", "Z": "value"}
    ),  # fmt: skip
    "combine": dict(inputs={"X": 0.0, "Y": 0.0, "Z": 0.0}, outputs={"Vector": "triple"}),
    "to_bw": dict(inputs={"Color": (0.5, 0.5, 0.5)}, outputs={"Val": "value"}),
    # 1 within Size / 2 (world units) of an edge of the mesh's triangles, else 0
    "wireframe": dict(inputs={"Size": 0.01}, outputs={"Fac": "value"}),
    # a black body's colour at Temperature kelvin, of luminance 1 (core.blackbody)
    "blackbody": dict(inputs={"Temperature": 1500.0}, outputs={"Color": "triple"}),
    # shading normals (a closure's Normal input)
    "bump": dict(
        inputs={"Strength": 1.0, "Distance": 1.0, "Height": 1.0},
        outputs={"Normal": "triple"},
        settings={"invert": False},
    ),  # fmt: skip
    "normal_map": dict(
        inputs={"Strength": 1.0, "Color": (0.5, 0.5, 1.0)},
        outputs={"Normal": "triple"},
        # strength_mix: Strength mixes the mapped vector as it is ("VECTOR", Cycles from 4.0
        # for an object not instanced) or made unit first ("UNIT", Cycles 3)
        settings={"space": "TANGENT", "strength_mix": "VECTOR"},
    ),  # fmt: skip
}
NORMAL_MAP_SPACES = ("TANGENT", "OBJECT", "WORLD")
NORMAL_MAP_MIXES = ("VECTOR", "UNIT")
# The attribute name a tangent-space Normal Map reads a mesh's corner_tangents by
# (core.kernels.attributes carries them as it does colours; no Blender attribute starts with
# a NUL)
TANGENT_ATTRIBUTE = "\0tangent"
# ... and the Wireframe node reads the distances to the hit triangle's edges by this one
# (computed at the hit, not stored: core.kernels.attributes)
EDGE_ATTRIBUTE = "\0edges"
# Microfacet distributions, in the order of core.kernels.microfacet's DIST_* numbers
DISTRIBUTIONS = ("GGX", "MULTI_GGX", "BECKMANN")
# What dims the layers under a rough coat (core.kernels.clear_coat): the mean Fresnel over
# its lobe (Cycles from 4.5), or the exact Fresnel at its normal (4.2)
COAT_ALBEDOS = ("LOBE", "NORMAL")
# The Voronoi texture's Feature and Distance Whitted evaluates, and its two cell hashes
# (core.kernels.voronoi), in the order of the kernel's numbers
VORONOI_FEATURES = ("F1", "F2", "SMOOTH_F1")
VORONOI_METRICS = ("EUCLIDEAN", "MANHATTAN", "CHEBYCHEV", "MINKOWSKI")
VORONOI_HASHES = ("LOOKUP3", "PCG")

MATH_OPERATIONS = ("ADD", "SUBTRACT", "MULTIPLY", "DIVIDE", "MULTIPLY_ADD", "POWER",
                   "MINIMUM", "MAXIMUM", "LESS_THAN", "GREATER_THAN", "ABSOLUTE", "SQRT",
                   "FLOOR", "CEIL", "FRACT", "MODULO", "SINE", "COSINE", "SNAP",
                   "ROUND", "SIGN", "EXPONENT", "LOGARITHM", "PINGPONG", "WRAP",
                   "SMOOTH_MIN", "SMOOTH_MAX", "COMPARE", "TRUNC", "INVERSE_SQRT",
                   "FLOORED_MODULO", "TANGENT", "ARCSINE", "ARCCOSINE", "ARCTANGENT",
                   "ARCTAN2", "SINH", "COSH", "TANH", "RADIANS", "DEGREES")  # fmt: skip
VECTOR_MATH_OPERATIONS = ("ADD", "SUBTRACT", "MULTIPLY", "DIVIDE", "MULTIPLY_ADD",
                          "CROSS_PRODUCT", "PROJECT", "REFLECT", "REFRACT", "FACEFORWARD",
                          "DOT_PRODUCT", "DISTANCE", "LENGTH", "SCALE", "NORMALIZE",
                          "ABSOLUTE", "POWER", "SIGN", "MINIMUM", "MAXIMUM", "FLOOR", "CEIL",
                          "FRACTION", "MODULO", "WRAP", "SNAP", "SINE", "COSINE",
                          "TANGENT")  # fmt: skip
MIX_BLENDS = ("MIX", "ADD", "MULTIPLY", "SUBTRACT", "SCREEN", "DIVIDE", "DIFFERENCE",
              "DARKEN", "LIGHTEN", "OVERLAY", "EXCLUSION", "BURN", "DODGE", "HUE",
              "SATURATION", "VALUE", "COLOR", "SOFT_LIGHT", "LINEAR_LIGHT")  # fmt: skip
GRADIENT_TYPES = ("LINEAR", "QUADRATIC", "EASING", "DIAGONAL", "RADIAL", "QUADRATIC_SPHERE",
                  "SPHERICAL")  # fmt: skip
MAPPING_TYPES = ("POINT", "TEXTURE", "VECTOR", "NORMAL")
WAVE_TYPES = ("BANDS", "RINGS")
WAVE_BANDS = ("X", "Y", "Z", "DIAGONAL")
WAVE_RINGS = ("X", "Y", "Z", "SPHERICAL")
WAVE_PROFILES = ("SIN", "SAW", "TRI")
# The rows of an RGB Curves node's table (Cycles' RAMP_TABLE_SIZE)
CURVE_TABLE_SIZE = 256
# The closures with a microfacet distribution
ROUGH_CLOSURES = ("principled", "glossy", "metallic", "glass", "refraction")
# The deepest chain of nodes a graph may have: the graph is walked recursively
MAX_GRAPH_DEPTH = 100
INTERPOLATIONS = ("Linear", "Closest", "Cubic", "Smart")
EXTENSIONS = ("REPEAT", "EXTEND", "CLIP", "MIRROR")
# (B-Spline, Cardinal and the HSV and HSL modes come from Blender baked to Linear stops, as
# Cycles bakes them: blender_addon.export.shader_nodes.ramp_table)
RAMP_INTERPOLATIONS = ("LINEAR", "CONSTANT", "EASE")


@dataclass(frozen=True, eq=False)
class Link:
    """The output `output` of `node`, feeding an input."""

    node: ShaderNode
    output: str = ""


@dataclass(eq=False)
class ShaderNode:
    kind: str
    inputs: dict = field(default_factory=dict)
    settings: dict = field(default_factory=dict)
    name: str = ""

    def input(self, name: str):
        """The value or Link on input `name`, or its default."""
        if name in self.inputs:
            return self.inputs[name]
        return SHADER_NODES[self.kind]["inputs"][name]

    def setting(self, name: str):
        if name in self.settings:
            return self.settings[name]
        return SHADER_NODES[self.kind].get("settings", {})[name]

    @property
    def is_closure(self) -> bool:
        return bool(SHADER_NODES.get(self.kind, {}).get("closure"))

    def validate(self, owner: str, seen: dict, depth: int = 0) -> None:
        """Check this node and those it links to (each once; `seen` marks the nodes on the
        current path "open", so a cycle is found)."""
        label = f"node '{self.name or self.kind}'"
        if depth > MAX_GRAPH_DEPTH:
            raise SceneError(owner, label, f"lies more than {MAX_GRAPH_DEPTH} nodes deep in "
                             "its graph: flatten it (nested node groups count)")  # fmt: skip
        if self.kind not in SHADER_NODES:
            raise SceneError(owner, label, f"unknown kind {self.kind!r}")
        if seen.get(id(self)) == "open":
            raise SceneError(owner, label, "is linked into itself (a cycle)")
        if id(self) in seen:
            return
        seen[id(self)] = "open"
        spec = SHADER_NODES[self.kind]
        for name, value in self.inputs.items():
            if name not in spec["inputs"]:
                raise SceneError(owner, f"{label} input {name!r}", "no such input")
            _check_input(owner, f"{label} input '{name}'", value, spec["inputs"][name], seen,
                         depth)  # fmt: skip
        for name in self.settings:
            if name not in spec.get("settings", {}):
                raise SceneError(owner, f"{label} setting {name!r}", "no such setting")
        _check_settings(owner, label, self)
        seen[id(self)] = "done"


def _check_input(owner, label, value, default, seen, depth) -> None:
    if isinstance(value, Link):
        if not isinstance(value.node, ShaderNode):
            raise SceneError(owner, label, "links to something that is not a ShaderNode")
        outputs = SHADER_NODES.get(value.node.kind, {}).get("outputs", {})
        shader_input = default is None and label.endswith(("Shader A'", "Shader B'"))
        if shader_input != value.node.is_closure:
            wanted = "a shader" if shader_input else "a value"
            raise SceneError(owner, label, f"needs {wanted}, got node '{value.node.kind}'")
        if not value.node.is_closure and value.output not in outputs:
            raise SceneError(owner, label, f"node '{value.node.kind}' has no output "
                             f"{value.output!r}; use one of {', '.join(outputs)}")  # fmt: skip
        value.node.validate(owner, seen, depth + 1)
        return
    if value is None:
        return
    v = np.asarray(value, float) if not isinstance(value, bool) else None
    if v is None or v.shape not in ((), (3,)) or not np.all(np.isfinite(v)):
        raise SceneError(owner, label, f"got {value!r}; use a finite number or three")


def _check_settings(owner, label, node) -> None:
    choices = {
        ("math", "operation"): MATH_OPERATIONS,
        ("mix_color", "blend"): MIX_BLENDS,
        ("vector_math", "operation"): VECTOR_MATH_OPERATIONS,
        ("wave", "type"): WAVE_TYPES,
        ("wave", "bands_direction"): WAVE_BANDS,
        ("wave", "rings_direction"): WAVE_RINGS,
        ("wave", "profile"): WAVE_PROFILES,
        ("gradient", "type"): GRADIENT_TYPES,
        ("mapping", "type"): MAPPING_TYPES,
        ("image", "interpolation"): INTERPOLATIONS,
        ("image", "extension"): EXTENSIONS,
        ("color_ramp", "interpolation"): RAMP_INTERPOLATIONS,
        ("normal_map", "space"): NORMAL_MAP_SPACES,
        ("normal_map", "strength_mix"): NORMAL_MAP_MIXES,
        ("voronoi", "feature"): VORONOI_FEATURES,
        ("voronoi", "distance"): VORONOI_METRICS,
        ("voronoi", "cell_hash"): VORONOI_HASHES,
        ("principled", "coat_albedo"): COAT_ALBEDOS,
        **{(kind, "distribution"): DISTRIBUTIONS for kind in ROUGH_CLOSURES},
    }
    for (kind, name), allowed in choices.items():
        if node.kind == kind and node.setting(name) not in allowed:
            given = node.setting(name)
            raise SceneError(owner, f"{label} {name}",
                             f"got {given!r}; use one of {', '.join(allowed)}")  # fmt: skip
    if node.kind == "brick":
        _check_brick(owner, label, node)
    if node.kind == "image":
        from .materials import Texture

        texture = node.setting("texture")
        if not isinstance(texture, Texture):
            raise SceneError(owner, f"{label} texture", f"got {texture!r}; need a Texture")
        texture.validate(owner)
    if node.kind == "attribute" and not isinstance(node.setting("name"), str):
        given = node.setting("name")
        raise SceneError(owner, f"{label} name", f'got {given!r}; use a text ("": the default)')
    if node.kind == "magic" and node.setting("depth") not in range(11):
        given = node.setting("depth")
        raise SceneError(owner, f"{label} depth", f"got {given!r}; use a whole number from 0 to 10")
    if node.kind == "white_noise" and node.setting("dimensions") not in (1, 2, 3, 4):
        given = node.setting("dimensions")
        raise SceneError(owner, f"{label} dimensions", f"got {given!r}; use 1, 2, 3 or 4")
    if node.kind == "rgb_curves":
        table = node.setting("table")
        low, high = node.setting("range")
        if table is None or np.shape(table) != (CURVE_TABLE_SIZE, 3):
            raise SceneError(owner, f"{label} table", f"give {CURVE_TABLE_SIZE} RGB rows")
        if not (np.all(np.isfinite(table)) and np.isfinite(low) and high > low):
            raise SceneError(owner, f"{label} range", "give finite numbers, the first below")
    if node.kind == "color_ramp":
        stops = node.setting("stops")
        if len(stops) < 1 or any(len(colour) != 4 for _, colour in stops):
            raise SceneError(owner, f"{label} stops", "give (position, RGBA) pairs, at least one")


def _check_brick(owner, label, node) -> None:
    """Brick's settings within Blender's own ranges."""
    ranges = {"offset": (0.0, 1.0), "squash": (0.0, 99.0)}
    for name, (low, high) in ranges.items():
        value = node.setting(name)
        if (
            isinstance(value, bool)
            or not isinstance(value, (int, float))
            or not low <= value <= high
        ):
            raise SceneError(
                owner, f"{label} {name}", f"got {value!r}; use a number from {low} to {high}"
            )
    for name in ("offset_frequency", "squash_frequency"):
        value = node.setting(name)
        if isinstance(value, bool) or not isinstance(value, int) or not 1 <= value <= 99:
            raise SceneError(
                owner, f"{label} {name}", f"got {value!r}; use a whole number from 1 to 99"
            )


def _closures(surface):
    """The closure nodes a graph's surface reaches, each once."""
    stack, seen = [surface], set()
    while stack:
        node = stack.pop()
        if node is None or id(node) in seen:
            continue
        seen.add(id(node))
        yield node
        for given in node.inputs.values():
            if isinstance(given, Link) and given.node.is_closure:
                stack.append(given.node)


def _given(node, name, above) -> bool:
    """Whether input `name` is linked (it may take any value) or set above `above`."""
    value = node.input(name)
    return isinstance(value, Link) or float(np.max(value)) > above


def emits(surface) -> bool:
    """Whether a graph can emit light: an Emission shader, or a Principled BSDF whose
    Emission Strength and Color are both linked or above 0, among its closures."""
    return any(
        node.kind == "emission"
        or (
            node.kind == "principled"
            and _given(node, "Emission Strength", 0.0)
            and _given(node, "Emission Color", 0.0)
        )
        for node in _closures(surface)
    )


def passes_light(surface, refraction_passes: bool = True) -> bool:
    """Whether a graph can let a shadow ray through its surface anywhere: a Transparent
    BSDF, or a Principled BSDF whose Alpha is linked or below 1, among its closures; and,
    when `refraction_passes` (the "attenuated" glass-shadow rule), a Glass or Refraction
    BSDF, or a Principled BSDF whose Transmission is linked or above 0."""
    refracting = ("glass", "refraction") if refraction_passes else ()
    for node in _closures(surface):
        if node.kind == "transparent" or node.kind in refracting:
            return True
        if node.kind == "principled":
            alpha = node.input("Alpha")
            if isinstance(alpha, Link) or float(alpha) < 1.0:
                return True
            if refraction_passes and _given(node, "Transmission", 0.0):
                return True
    return False


def attribute_names(surfaces) -> list[str]:
    """The colour attribute names the graphs' Attribute nodes read, each once, sorted (the
    kernels' numbering of them, core.kernels.attributes)."""
    names = set()
    for surface in surfaces:
        stack, seen = [surface], set()
        while stack:
            node = stack.pop()
            if node is None or id(node) in seen:
                continue
            seen.add(id(node))
            if node.kind == "attribute":
                names.add(node.setting("name"))
            if node.kind == "normal_map" and node.setting("space") == "TANGENT":
                names.add(TANGENT_ATTRIBUTE)
            if node.kind == "wireframe":
                names.add(EDGE_ATTRIBUTE)
            stack.extend(g.node for g in node.inputs.values() if isinstance(g, Link))
    return sorted(names)


def coated(node) -> bool:
    """Whether a closure node is a layered Principled BSDF whose Coat Weight is linked or
    above 0 (a clear coat, core.kernels.clear_coat)."""
    return (
        node.kind == "principled"
        and bool(node.setting("layered"))
        and _given(node, "Coat Weight", 0.0)
    )


def has_clear_coat(surface) -> bool:
    """Whether a graph has a coated closure (`coated`)."""
    return any(map(coated, _closures(surface)))


def is_translucent(surface) -> bool:
    """Whether a graph has a Translucent BSDF among its closures."""
    return any(node.kind == "translucent" for node in _closures(surface))


def is_rough(surface) -> bool:
    """Whether a graph has a closure with a microfacet lobe whose Roughness is linked or
    above 0 (ROUGH_CLOSURES): one whose rays Glossy Samples may spread."""
    return any(
        node.kind in ROUGH_CLOSURES and _given(node, "Roughness", 0.0)
        for node in _closures(surface)
    )


def sends_caustics(surface, reflective: bool, refractive: bool) -> bool:
    """Whether a graph may send light on as a caustic: reflect it as a mirror (Glossy,
    Metallic, Glass, a Principled BSDF whose Metallic or Transmission is linked or above 0),
    when `reflective`; refract it (Glass, Refraction, Principled Transmission), when
    `refractive`."""
    for node in _closures(surface):
        kind = node.kind
        if reflective and kind in ("glossy", "metallic", "glass"):
            return True
        if refractive and kind in ("glass", "refraction"):
            return True
        if kind == "principled":
            if reflective and (_given(node, "Metallic", 0.0) or _given(node, "Transmission", 0.0)):
                return True
            if refractive and _given(node, "Transmission", 0.0):
                return True
    return False
