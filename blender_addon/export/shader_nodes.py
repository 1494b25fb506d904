"""A material's node tree, read as Cycles reads it, into a core shader graph
(core.model.shader): from the active Material Output's Surface socket down, through reroutes
and node groups, each node Whitted evaluates becoming a core `ShaderNode` (the kernels run it
per hit, or the compile folds it). What Whitted cannot evaluate is noted, with what was used
in its place, for the material's one warning.
"""

from __future__ import annotations

import numpy as np

from .. import core
from ..compat import COAT_ALBEDO, NORMAL_MAP_MIX, PRINCIPLED_LAYERED, VORONOI_CELL_HASH
from .shader_graph import Feed, feed_of, node_label, output_node

# Principled BSDF inputs that change the look but are not modelled, with the value that
# changes nothing and what is used instead
_UNMODELLED = (
    ("Clearcoat", 0.0, "no clearcoat"),
    ("Sheen Weight", 0.0, "no sheen"),
    ("Sheen", 0.0, "no sheen"),
    ("Subsurface Weight", 0.0, "the base colour as diffuse"),
    ("Subsurface", 0.0, "the base colour as diffuse"),
    ("Anisotropic", 0.0, "isotropic"),
    ("Thin Film Thickness", 0.0, "no thin film"),
)
NO_ABSORPTION = (0.0, 0.0, 0.0)
# Shaders Whitted does not model, drawn as the nearest it does (with a warning), not black:
# Blender node.type -> (core kind, what the warning says is used)
_STAND_INS = {
    # light leaving near where it entered: at Whitted's scale, a diffuse of the colour
    "SUBSURFACE_SCATTERING": ("diffuse", "a Diffuse BSDF of its Color"),
    "BSDF_TOON": ("diffuse", "a Diffuse BSDF of its Color"),
    "BSDF_HAIR": ("diffuse", "a Diffuse BSDF of its Color"),
    "BSDF_HAIR_PRINCIPLED": ("diffuse", "a Diffuse BSDF of its Color"),
    # unlinked Position and Direction: the ray goes on through the surface, as through glass
    # of index 1
    "BSDF_RAY_PORTAL": ("transparent", "a Transparent BSDF of its Color"),
}
# Blender's Math operations Whitted computes (the others: noted, their A used)
MATH = set(core.model.shader.MATH_OPERATIONS)
BLENDS = set(core.model.shader.MIX_BLENDS)
VECTOR_MATH = set(core.model.shader.VECTOR_MATH_OPERATIONS)
# Value nodes: Blender node.type -> (core kind, {Blender output identifier or name: core
# output name})
OUTPUTS = {
    "TEX_IMAGE": ("image", {"Color": "Color", "Alpha": "Alpha"}),
    "TEX_COORD": (
        "tex_coord",
        {"UV": "UV", "Generated": "Generated", "Object": "Object", "Normal": "Normal"},
    ),  # fmt: skip
    "UVMAP": ("tex_coord", {"UV": "UV"}),
    # (Tangent, Parametric, Pointiness and Random Per Island are not evaluated: noted)
    "NEW_GEOMETRY": (
        "geometry",
        {name: name for name in ("Position", "Normal", "True Normal", "Incoming", "Backfacing")},
    ),  # fmt: skip
    # a mesh's colour attribute (core.kernels.attributes)
    "VERTEX_COLOR": ("attribute", {"Color": "Color", "Alpha": "Alpha"}),
    "ATTRIBUTE": (
        "attribute",
        {"Color": "Color", "Vector": "Vector", "Fac": "Fac", "Alpha": "Alpha"},
    ),  # fmt: skip
    # (Is Singular Ray and Is Volume Scatter Ray are not evaluated: noted)
    "LIGHT_PATH": ("light_path", {name: name for name in core.model.shader.LIGHT_PATH_OUTPUTS}),
    "FRESNEL": ("fresnel", {"Fac": "Fac"}),
    "LAYER_WEIGHT": ("layer_weight", {"Fresnel": "Fresnel", "Facing": "Facing"}),
    "MAPPING": ("mapping", {"Vector": "Vector"}),
    "MATH": ("math", {"Value": "Value"}),
    "VECT_MATH": ("vector_math", {"Vector": "Vector", "Value": "Value"}),
    "MIX_RGB": ("mix_color", {"Color": "Color"}),
    "MIX": (
        "mix_color",
        {
            "Result": "Color",
            "Result_Color": "Color",
            "Result_Float": "Color",
            "Result_Vector": "Color",
        },
    ),  # fmt: skip
    "INVERT": ("invert", {"Color": "Color"}),
    "GAMMA": ("gamma", {"Color": "Color"}),
    "BRIGHTCONTRAST": ("bright_contrast", {"Color": "Color"}),
    "HUE_SAT": ("hsv", {"Color": "Color"}),
    "VALTORGB": ("color_ramp", {"Color": "Color", "Alpha": "Alpha"}),
    "CURVE_RGB": ("rgb_curves", {"Color": "Color"}),
    "SEPXYZ": ("separate", {"X": "X", "Y": "Y", "Z": "Z"}),
    "SEPRGB": ("separate", {"R": "X", "G": "Y", "B": "Z"}),
    "SEPARATE_COLOR": ("separate", {"Red": "X", "Green": "Y", "Blue": "Z"}),
    "COMBXYZ": ("combine", {"Vector": "Vector"}),
    "COMBRGB": ("combine", {"Image": "Vector"}),
    "COMBINE_COLOR": ("combine", {"Color": "Vector"}),
    "RGBTOBW": ("to_bw", {"Val": "Val"}),
    "BLACKBODY": ("blackbody", {"Color": "Color"}),
    "WIREFRAME": ("wireframe", {"Fac": "Fac"}),
    "TEX_CHECKER": ("checker", {"Color": "Color", "Fac": "Fac"}),
    "TEX_GRADIENT": ("gradient", {"Color": "Color", "Fac": "Fac"}),
    "TEX_MAGIC": ("magic", {"Color": "Color", "Fac": "Fac"}),
    "TEX_WAVE": ("wave", {"Color": "Color", "Fac": "Fac"}),
    "TEX_WHITE_NOISE": ("white_noise", {"Value": "Value", "Color": "Color"}),
    "TEX_BRICK": ("brick", {"Color": "Color", "Fac": "Fac"}),
    "TEX_NOISE": ("noise", {"Fac": "Fac", "Color": "Color"}),
    "TEX_VORONOI": ("voronoi", {"Distance": "Distance", "Color": "Color", "Position": "Position"}),
    "BUMP": ("bump", {"Normal": "Normal"}),
    "NORMAL_MAP": ("normal_map", {"Normal": "Normal"}),
}


class GraphReader:
    """Reads one material's tree into a core graph; `problems` lists what it could not
    honour, each once; `image_texture(image)` makes a core Texture of a Blender image."""

    def __init__(self, material, image_texture):
        self.material = material
        self.image_texture = image_texture
        self.problems: list[str] = []
        self.made: dict = {}  # (node, group path) -> core ShaderNode
        self.depth = 0  # value nodes being read, one inside the other
        self.displaced = None  # the Material Output's Displacement, as a bump normal
        # the medium inside: the Material Output's Volume Absorption (core Material.absorption)
        self.absorption = NO_ABSORPTION

    def note(self, text: str) -> None:
        if text not in self.problems:
            self.problems.append(text)

    def read(self, tree) -> core.ShaderNode | None:
        """The closure node the surface renders from, or None (nothing linked: black)."""
        output = output_node(tree)
        if output is None:
            self.note("its node tree has no Material Output: rendered black")
            return None
        self.absorption = self._volume(output)
        self.displaced = self._displacement(output)
        return self.shader(feed_of(output.inputs["Surface"]))

    def _volume(self, output) -> tuple:
        """The absorption coefficient (RGB, per unit of world length) of the medium the
        surface encloses: a Volume Absorption on the Material Output's Volume, as Cycles
        computes it, (1 - Color) x Density (glTF's attenuation imports as one). Any other
        volume is noted and not rendered."""
        socket = output.inputs.get("Volume")
        feed = feed_of(socket) if socket is not None else None
        if feed is None or feed.node is None or getattr(feed.node, "mute", False):
            return NO_ABSORPTION
        node = feed.node
        if node.type != "VOLUME_ABSORPTION":
            self.note(f"{node_label(node)} on the Material Output's Volume is not rendered "
                      "(used: no volume; a Volume Absorption is rendered)")  # fmt: skip
            return NO_ABSORPTION
        colour = self._volume_input(node, feed.groups, "Color")
        density = max(0.0, float(self._volume_input(node, feed.groups, "Density")))
        if max(colour) > 1.0:  # Cycles would give light back: a medium that glows
            self.note(f"{node_label(node)}'s Color above 1 (used: 1 there, no absorption)")
        return tuple((1.0 - min(1.0, max(0.0, c))) * density for c in colour)

    def _volume_input(self, node, groups, name):
        """A Volume Absorption input's constant: a medium is uniform to Whitted (Cycles'
        homogeneous volume); what is linked to it is evaluated only if it is a constant."""
        feed = feed_of(node.inputs[name], groups)
        if feed.node is None or feed.node.type in ("VALUE", "RGB"):
            return _constant(feed.socket)
        value = _constant(node.inputs[name])
        self.note(f"node {node_label(feed.node)} feeding {node_label(node)}'s {name}: a "
                  f"medium is uniform (used: its value {_shown(value)})")  # fmt: skip
        return value

    def _displacement(self, output):
        """The Material Output's Displacement as a Link to the bump normal it makes (Cycles'
        Displacement Only Bump, as Whitted renders every method), or None."""
        socket = output.inputs.get("Displacement")
        if socket is None or feed_of(socket).node is None:
            return None
        method = getattr(getattr(self.material, "cycles", None), "displacement_method", "BUMP")
        if method not in ("BUMP", "DISPLACEMENT_BUMP"):
            self.note(f"Displacement Method {method.title()} (used: Bump Only)")
        feed = feed_of(socket)
        if feed.node.type != "DISPLACEMENT":
            self.note(f"node {node_label(feed.node)} on the Material Output's Displacement "
                      "(used: the surface's own normal; a Displacement node is read)")  # fmt: skip
            return None
        node = feed.node
        if getattr(node, "space", "OBJECT") != "OBJECT":
            self.note(f"{node_label(node)}'s {node.space.title()} space (used: Object)")
        # Its height along the normal, (Height - Midlevel) x Scale, as a bump of distance 1
        v = self.value
        offset = core.ShaderNode("math", {"A": v(node, feed.groups, "Height"),
                                          "B": v(node, feed.groups, "Midlevel")},
                                 {"operation": "SUBTRACT"}, name=node.name)  # fmt: skip
        height = core.ShaderNode("math", {"A": core.Link(offset, "Value"),
                                          "B": v(node, feed.groups, "Scale")},
                                 {"operation": "MULTIPLY"}, name=node.name)  # fmt: skip
        bump = core.ShaderNode("bump", {"Height": core.Link(height, "Value"), "Distance": 1.0},
                               name=node.name)  # fmt: skip
        return core.Link(bump, "Normal")

    # shaders

    def shader(self, feed: Feed) -> core.ShaderNode | None:
        node = feed.node
        if node is None:
            return None  # an unlinked shader socket adds nothing, as in Cycles
        if getattr(node, "mute", False):
            for socket in node.inputs:  # a muted node passes its first linked shader through
                if socket.type == "SHADER" and socket.is_linked:
                    return self.shader(feed_of(socket, feed.groups))
            return None
        key = (node.as_pointer(), tuple(g.as_pointer() for g in feed.groups))
        if key not in self.made:
            self.made[key] = self._shader(node, feed.groups)
        return self.made[key]

    def _shader(self, node, groups):
        kind = node.type
        v = self.value
        if kind in ("MIX_SHADER", "ADD_SHADER"):
            first = 1 if kind == "MIX_SHADER" else 0
            made = core.ShaderNode(kind.lower(), name=node.name)
            if kind == "MIX_SHADER":
                made.inputs["Fac"] = v(node, groups, "Fac")
            for name, socket in zip(("Shader A", "Shader B"), node.inputs[first : first + 2],
                                    strict=True):  # fmt: skip
                inner = self.shader(feed_of(socket, groups))
                if inner is not None:
                    made.inputs[name] = core.Link(inner)
            return made
        if kind == "BSDF_PRINCIPLED":
            return self._principled(node, groups)
        simple = {
            "BSDF_DIFFUSE": ("diffuse", ("Color", "Roughness")),
            "BSDF_TRANSLUCENT": ("translucent", ("Color",)),
            "BSDF_GLOSSY": ("glossy", ("Color", "Roughness")),
            "BSDF_ANISOTROPIC": ("glossy", ("Color", "Roughness")),
            "BSDF_METALLIC": ("metallic", ("Base Color", "Edge Tint", "Roughness")),
            "BSDF_GLASS": ("glass", ("Color", "Roughness", "IOR")),
            "BSDF_REFRACTION": ("refraction", ("Color", "Roughness", "IOR")),
            "BSDF_TRANSPARENT": ("transparent", ("Color",)),
            "EMISSION": ("emission", ("Color", "Strength")),
            "HOLDOUT": ("holdout", ()),
        }
        if kind in _STAND_INS:
            return self._stand_in(node, groups)
        if kind not in simple:
            self.note(f"node {node_label(node)} is not a shader Whitted renders (used: black)")
            return None
        core_kind, names = simple[kind]
        made = core.ShaderNode(core_kind, name=node.name)
        for name in names:
            made.inputs[name] = v(node, groups, name)
        self._distribution(node, made)
        if kind == "BSDF_METALLIC" and getattr(node, "fresnel_type", "F82") != "F82":
            self.note(f"{node_label(node)}'s Physical Conductor Fresnel (used: F82 Tint)")
        self._normal(made, node, groups)
        return made

    def _stand_in(self, node, groups):
        """A shader Whitted does not model drawn as the nearest one it does (_STAND_INS),
        named in a warning: never black, as a missing shader would be."""
        core_kind, used = _STAND_INS[node.type]
        inputs = {"Color": self.value(node, groups, "Color")}
        if node.type == "BSDF_TOON" and getattr(node, "component", "DIFFUSE") == "GLOSSY":
            core_kind, used = "glossy", "a Glossy BSDF of its Color, Size as roughness"
            inputs["Roughness"] = self.value(node, groups, "Size")
        if node.type == "BSDF_RAY_PORTAL":
            for name in ("Position", "Direction"):
                self.linked(node, groups, name, "the ray goes on where it is")
        made = core.ShaderNode(core_kind, inputs, name=node.name)
        self.note(f"{node_label(node)} is not modelled (used: {used})")
        self._normal(made, node, groups)
        return made

    def _distribution(self, node, made) -> None:
        """A rough lobe's microfacet distribution (core.kernels.microfacet): GGX,
        Multiscatter GGX and Beckmann as named (Beckmann's rays spread by Glossy Samples
        are GGX's: noted when rough); a Sharp one (before 4.0) has no roughness, and
        Ashikhmin-Shirley is noted when rough (drawn as Multiscatter GGX)."""
        distribution = getattr(node, "distribution", "GGX")
        settings = core.model.shader.SHADER_NODES[made.kind].get("settings", {})
        if "Roughness" not in made.inputs or "distribution" not in settings:
            return
        rough = isinstance(made.inputs["Roughness"], core.Link) or made.inputs["Roughness"] > 0.0
        if distribution in core.model.shader.DISTRIBUTIONS:
            made.settings["distribution"] = distribution
            if distribution == "BECKMANN" and rough:  # core.kernels.glossy samples GGX's
                self.note(f"{node_label(node)}'s Beckmann distribution (used: GGX for the "
                          "rays Glossy Samples spread; its glint is Beckmann's)")  # fmt: skip
        elif distribution == "SHARP":
            made.inputs["Roughness"] = 0.0
        else:
            made.settings["distribution"] = "MULTI_GGX"
            if rough:
                shown = distribution.replace("_", "-").title()
                self.note(f"{node_label(node)}'s {shown} distribution (used: Multiscatter GGX)")

    def _normal(self, made, node, groups) -> None:
        """A closure's Normal input: what feeds it, else the displacement's bump normal."""
        socket = node.inputs.get("Normal")
        if socket is None or "Normal" not in core.model.shader.SHADER_NODES[made.kind]["inputs"]:
            return
        if feed_of(socket, groups).node is not None:
            made.inputs["Normal"] = self.value(node, groups, "Normal")
        elif self.displaced is not None:
            made.inputs["Normal"] = self.displaced

    def _principled(self, node, groups):
        for name, neutral, used in _UNMODELLED:
            socket = node.inputs.get(name)
            if socket is None:
                continue
            feed = feed_of(socket, groups)
            if feed.node is not None:  # a texture or any node may make it non-neutral
                self.note(f"{node_label(node)}'s {name}, driven by node "
                          f"{node_label(feed.node)}, is not modelled (used: {used})")  # fmt: skip
            elif _number(feed.socket) != neutral:  # its value, or the group's input's
                self.note(f"{node_label(node)}'s {name} is not modelled (used: {used})")
        for name in ("Clearcoat Normal", "Tangent"):
            self.linked(node, groups, name, "the surface's own normal")
        v = self.value
        made = core.ShaderNode("principled", name=node.name,
                               settings={"layered": PRINCIPLED_LAYERED,
                                         "coat_albedo": COAT_ALBEDO})  # fmt: skip
        renamed = {
            "Base Color": ("Base Color",),
            "Metallic": ("Metallic",),
            "Roughness": ("Roughness",),
            "Diffuse Roughness": ("Diffuse Roughness",),
            "IOR": ("IOR",),
            "Alpha": ("Alpha",),
            "Transmission": ("Transmission Weight", "Transmission"),
            "Emission Color": ("Emission Color", "Emission"),
            "Emission Strength": ("Emission Strength",),
            "Specular": ("Specular IOR Level", "Specular"),
            "Specular Tint": ("Specular Tint",),
            "Coat Weight": ("Coat Weight",),
            "Coat Roughness": ("Coat Roughness",),
            "Coat IOR": ("Coat IOR",),
            "Coat Tint": ("Coat Tint",),
        }
        for core_name, names in renamed.items():
            name = next((n for n in names if node.inputs.get(n) is not None), None)
            if name is not None:
                made.inputs[core_name] = v(node, groups, name)
        self._distribution(node, made)
        self._normal(made, node, groups)
        self._coat_normal(made, node, groups)
        return made

    def _coat_normal(self, made, node, groups) -> None:
        """The Coat Normal: what feeds it, else the displacement's bump normal (Cycles'
        coat takes the surface's normal, not the Normal input's)."""
        socket = node.inputs.get("Coat Normal")
        if socket is None:
            return
        if feed_of(socket, groups).node is not None:
            made.inputs["Coat Normal"] = self.value(node, groups, "Coat Normal")
        elif self.displaced is not None:
            made.inputs["Coat Normal"] = self.displaced

    # values

    def value(self, node, groups, name):
        """What feeds input `name` of `node`: its constant, or a Link to the core node made
        of what is linked to it (the input's own value, noted, where Whitted cannot)."""
        return self._socket_value(node, groups, node.inputs[name])

    def _value_node(self, feed: Feed):
        """A Link to the core node computing the fed output, or None when Whitted cannot."""
        node, socket = feed.node, feed.socket
        if node.type in ("VALUE", "RGB"):
            return _constant(socket)
        if node.type not in OUTPUTS:
            return None
        kind, names = OUTPUTS[node.type]
        # by identifier first: names change across versions (Fac became Factor in 5.0)
        output = names.get(socket.identifier, names.get(socket.name))
        if output is None:
            self.note(f"{node_label(node)}'s output {socket.name} is not evaluated")
            return None
        key = (node.as_pointer(), tuple(g.as_pointer() for g in feed.groups))
        if key not in self.made:
            self.made[key] = self._make_value_node(node, feed.groups, kind)
        made = self.made[key]
        return None if made is None else core.Link(made, output)

    def _make_value_node(self, node, groups, kind):
        v = self.value
        made = core.ShaderNode(kind, name=node.name)
        t = node.type
        if t == "TEX_IMAGE":
            if node.image is None:
                return None
            made.settings["texture"] = self.image_texture(node.image)
            interpolation = node.interpolation if node.interpolation in ("Linear", "Closest") \
                else "Linear"  # fmt: skip
            if node.interpolation not in ("Linear", "Closest"):
                self.note(f"{node_label(node)}'s {node.interpolation} interpolation (used: "
                          "Linear)")  # fmt: skip
            made.settings["interpolation"] = interpolation
            made.settings["extension"] = getattr(node, "extension", "REPEAT")
            if node.projection != "FLAT":
                self.note(f"{node_label(node)}'s {node.projection.title()} projection (used: "
                          "Flat)")  # fmt: skip
            made.inputs["Vector"] = self._vector(node, groups, "Vector")
        elif t == "VERTEX_COLOR":
            made.settings["name"] = node.layer_name
        elif t == "ATTRIBUTE":
            if node.attribute_type != "GEOMETRY":  # an object's, instancer's, view layer's
                return None
            made.settings["name"] = node.attribute_name
        elif t in ("TEX_CHECKER", "TEX_GRADIENT"):
            made.inputs["Vector"] = self._vector(node, groups, "Vector")
            if t == "TEX_CHECKER":
                for name in ("Color1", "Color2", "Scale"):
                    made.inputs[name] = v(node, groups, name)
            else:
                made.settings["type"] = node.gradient_type
        elif t == "TEX_WAVE":
            made.inputs["Vector"] = self._vector(node, groups, "Vector")
            for name in ("Scale", "Distortion", "Detail", "Detail Scale", "Detail Roughness",
                         "Phase Offset"):  # fmt: skip
                if node.inputs.get(name) is not None:  # (Detail Roughness and Phase: 2.83 on)
                    made.inputs[name] = v(node, groups, name)
            made.settings.update(type=node.wave_type, bands_direction=node.bands_direction,
                                 rings_direction=node.rings_direction,
                                 profile=node.wave_profile)  # fmt: skip
        elif t == "TEX_WHITE_NOISE":
            made.settings["dimensions"] = int(node.noise_dimensions[0])
            made.inputs["Vector"] = self._vector(node, groups, "Vector")
            if node.inputs.get("W") is not None:  # (5.0 hides what a dimension leaves out)
                made.inputs["W"] = v(node, groups, "W")
            if made.inputs["Vector"] is None and made.settings["dimensions"] > 1:
                self.note(f"{node_label(node)}'s unlinked Vector (Cycles: the point's "
                          "position; used: Generated coordinates)")  # fmt: skip
        elif t == "TEX_MAGIC":
            made.inputs["Vector"] = self._vector(node, groups, "Vector")
            for name in ("Scale", "Distortion"):
                made.inputs[name] = v(node, groups, name)
            made.settings["depth"] = int(node.turbulence_depth)
        elif t == "TEX_BRICK":
            made.inputs["Vector"] = self._vector(node, groups, "Vector")
            for name in ("Color1", "Color2", "Mortar", "Scale", "Mortar Size", "Mortar Smooth",
                         "Bias", "Brick Width", "Row Height"):  # fmt: skip
                made.inputs[name] = v(node, groups, name)
            for name in ("offset", "offset_frequency", "squash", "squash_frequency"):
                made.settings[name] = getattr(node, name)
        elif t == "TEX_NOISE":
            self._noise(node, groups, made)
        elif t == "TEX_VORONOI":
            self._voronoi(node, groups, made)
        elif t == "TEX_COORD":
            if getattr(node, "object", None) is not None:
                self.note(f"{node_label(node)}'s Object (used: the surface's own object)")
        elif t == "UVMAP":
            pass  # the active UV map is exported
        elif t in ("FRESNEL", "LAYER_WEIGHT"):
            name = "IOR" if t == "FRESNEL" else "Blend"
            made.inputs[name] = v(node, groups, name)
            self._normal(made, node, groups)  # linked, or the displacement's bump normal
        elif t == "MAPPING":
            made.settings["type"] = node.vector_type
            for name in ("Vector", "Location", "Rotation", "Scale"):
                if node.inputs.get(name) is not None and node.inputs[name].enabled:
                    made.inputs[name] = v(node, groups, name)
        elif t == "MATH":
            operation = node.operation if node.operation in MATH else "ADD"
            if node.operation not in MATH:
                self.note(f"{node_label(node)}'s {node.operation.title()} (used: Add)")
            made.settings.update(operation=operation, clamp=bool(node.use_clamp))
            for core_name, socket in zip(("A", "B", "C"), node.inputs, strict=False):
                made.inputs[core_name] = self._socket_value(node, groups, socket)
        elif t == "VECT_MATH":
            if node.operation not in core.model.shader.VECTOR_MATH_OPERATIONS:
                self.note(f"{node_label(node)}'s {node.operation.title()} (used: Add)")
            operation = node.operation if node.operation in VECTOR_MATH else "ADD"
            made.settings["operation"] = operation
            names = ("A", "B", "C", "Scale")
            for core_name, socket in zip(names, node.inputs, strict=False):
                made.inputs[core_name] = self._socket_value(node, groups, socket)
        elif t in ("MIX_RGB", "MIX"):
            blend = node.blend_type if node.blend_type in BLENDS else "MIX"
            if node.blend_type not in BLENDS:
                self.note(f"{node_label(node)}'s {node.blend_type.title()} (used: Mix)")
            clamp = getattr(node, "use_clamp", False) or getattr(node, "clamp_result", False)
            made.settings.update(blend=blend, clamp=bool(clamp))
            for core_name, socket in zip(("Fac", "A", "B"), _mix_inputs(node), strict=True):
                made.inputs[core_name] = self._socket_value(node, groups, socket)
        elif t == "CURVE_RGB":
            made.settings["table"], made.settings["range"] = curves_table(node.mapping)
            made.settings["extrapolate"] = node.mapping.extend == "EXTRAPOLATED"
            made.inputs.update(Fac=v(node, groups, "Fac"), Color=v(node, groups, "Color"))
        elif t == "VALTORGB":
            ramp = node.color_ramp
            made.settings["stops"] = tuple((e.position, tuple(e.color)) for e in ramp.elements)
            interpolation = ramp.interpolation
            if interpolation not in ("LINEAR", "CONSTANT", "EASE") or ramp.color_mode != "RGB":
                # B-Spline, Cardinal, HSV and HSL: the ramp as Cycles bakes it, Blender's own
                # curve at RAMP_TABLE_SIZE points, linear between them
                made.settings["stops"] = ramp_table(ramp)
                interpolation = "LINEAR"
            made.settings["interpolation"] = interpolation
            made.inputs["Fac"] = v(node, groups, "Fac")
        elif t in ("SEPXYZ", "SEPRGB", "SEPARATE_COLOR"):
            if getattr(node, "mode", "RGB") != "RGB":
                self.note(f"{node_label(node)}'s {node.mode} mode (used: RGB)")
            made.inputs["Vector"] = self._socket_value(node, groups, node.inputs[0])
        elif t in ("COMBXYZ", "COMBRGB", "COMBINE_COLOR"):
            if getattr(node, "mode", "RGB") != "RGB":
                self.note(f"{node_label(node)}'s {node.mode} mode (used: RGB)")
            for core_name, socket in zip(("X", "Y", "Z"), node.inputs, strict=False):
                made.inputs[core_name] = self._socket_value(node, groups, socket)
        elif t == "INVERT":
            made.inputs.update(Fac=v(node, groups, "Fac"), Color=v(node, groups, "Color"))
        elif t == "GAMMA":
            made.inputs.update(Color=v(node, groups, "Color"), Gamma=v(node, groups, "Gamma"))
        elif t == "BRIGHTCONTRAST":
            made.inputs.update(Color=v(node, groups, "Color"), Bright=v(node, groups, "Bright"),
                               Contrast=v(node, groups, "Contrast"))  # fmt: skip
        elif t == "HUE_SAT":
            for name in ("Hue", "Saturation", "Value", "Fac", "Color"):
                made.inputs[name] = v(node, groups, name)
        elif t == "RGBTOBW":
            made.inputs["Color"] = v(node, groups, "Color")
        elif t == "BLACKBODY":
            made.inputs["Temperature"] = v(node, groups, "Temperature")
        elif t == "WIREFRAME":
            made.inputs["Size"] = v(node, groups, "Size")
            if node.use_pixel_size:
                self.note(f"{node_label(node)}'s Pixel Size (used: Size in scene units)")
        elif t == "BUMP":
            for name in ("Strength", "Distance", "Height"):
                made.inputs[name] = v(node, groups, name)
            made.settings["invert"] = bool(node.invert)
            width = node.inputs.get("Filter Width")
            if width is not None and _number(node.inputs["Filter Width"]) > 0.1 + 1e-6:
                self.note(f"{node_label(node)}'s Filter Width above 0.1 (used: the height's "
                          "slope at the point)")  # fmt: skip
            self.linked(node, groups, "Normal", "the surface's own normal, bumped")
        elif t == "NORMAL_MAP":
            space = node.space if node.space in ("TANGENT", "OBJECT", "WORLD") else "OBJECT"
            if node.space != space:
                self.note(f"{node_label(node)}'s {node.space.title()} space (used: Object)")
            made.settings["space"] = space
            made.settings["strength_mix"] = NORMAL_MAP_MIX
            for name in ("Strength", "Color"):
                made.inputs[name] = v(node, groups, name)
        return made

    def _noise(self, node, groups, made) -> None:
        """The Noise texture: 3D fractal Brownian motion, as Blender's default (Lacunarity
        and Normalize came with 4.0, Noise Type with 4.1); other kinds are noted."""
        made.inputs["Vector"] = self._vector(node, groups, "Vector")
        for name in ("Scale", "Detail", "Roughness", "Lacunarity", "Distortion"):
            if node.inputs.get(name) is not None:
                made.inputs[name] = self.value(node, groups, name)
        made.settings["normalize"] = bool(getattr(node, "normalize", True))
        if node.noise_dimensions != "3D":
            self.note(f"{node_label(node)}'s {node.noise_dimensions} dimensions (used: 3D)")
        kind = getattr(node, "noise_type", "FBM")
        if kind != "FBM":
            self.note(f"{node_label(node)}'s {kind.replace('_', ' ').title()} type (used: fBM)")

    def _voronoi(self, node, groups, made) -> None:
        """The Voronoi texture: 3D, features F1, F2 and Smooth F1, every distance metric, fractal
        octaves (Detail, Roughness, Lacunarity and Normalize came with 4.0), with the cell
        hash of this Blender's Cycles; other dimensions and features are noted."""
        made.inputs["Vector"] = self._vector(node, groups, "Vector")
        names = ("Scale", "Detail", "Roughness", "Lacunarity", "Exponent", "Randomness",
                 "Smoothness")  # fmt: skip
        for name in names:
            if node.inputs.get(name) is not None:
                made.inputs[name] = self.value(node, groups, name)
        made.settings["normalize"] = bool(getattr(node, "normalize", False))
        made.settings["cell_hash"] = VORONOI_CELL_HASH
        made.settings["distance"] = node.distance
        if node.feature in core.model.shader.VORONOI_FEATURES:
            made.settings["feature"] = node.feature
        else:
            shown = node.feature.replace("_", " ").title()
            self.note(f"{node_label(node)}'s {shown} feature (used: F1)")
        if node.voronoi_dimensions != "3D":
            self.note(f"{node_label(node)}'s {node.voronoi_dimensions} dimensions (used: 3D)")

    def _vector(self, node, groups, name):
        """A texture's Vector: what feeds it, or None (its own default coordinates)."""
        socket = node.inputs.get(name)
        if socket is None or feed_of(socket, groups).node is None:
            return None
        return self.value(node, groups, name)

    def _socket_value(self, node, groups, socket):
        """`value` for a socket given as itself (nodes whose inputs share names)."""
        feed = feed_of(socket, groups)
        if feed.node is None:
            return _constant(feed.socket)
        if self.depth >= core.model.shader.MAX_GRAPH_DEPTH:
            made = None  # deeper than the core walks: the socket's own value, noted below
        else:
            self.depth += 1
            made = self._value_node(feed)
            self.depth -= 1
        if made is None:
            fallback = _constant(socket)
            used = _shown(fallback)
            self.note(f"node {node_label(feed.node)} feeding {node_label(node)}'s "
                      f"{socket.name} is not evaluated (used: its value {used})")  # fmt: skip
            return fallback
        return made

    def linked(self, node, groups, name, what: str) -> None:
        """Note an input Whitted does not read, when something feeds it."""
        socket = node.inputs.get(name)
        if socket is not None and feed_of(socket, groups).node is not None:
            self.note(f"{node_label(node)}'s {name} is not read (used: {what})")


def curves_table(mapping):
    """(table, range) of an RGB Curves node's curve mapping, as Cycles bakes it: x over 0..1
    widened to the curves' points (the lowest first point, the highest last one), each
    channel's curve applied after the combined C curve (Blender keeps them as R, G, B, C)."""
    mapping.initialize()
    curves = mapping.curves
    low = min(0.0, *(curve.points[0].location[0] for curve in curves))
    high = max(1.0, *(curve.points[-1].location[0] for curve in curves))
    size = core.model.shader.CURVE_TABLE_SIZE
    table = np.empty((size, 3))
    for i in range(size):
        x = low + (high - low) * i / (size - 1)
        combined = mapping.evaluate(curves[3], x)
        for channel in range(3):
            table[i, channel] = mapping.evaluate(curves[channel], combined)
    return table, (low, high)


# The points of a Color Ramp Cycles bakes (its RAMP_TABLE_SIZE), looked up linearly
RAMP_TABLE_SIZE = 256


def ramp_table(ramp) -> tuple:
    """A Color Ramp as Cycles renders it: Blender's own evaluation at RAMP_TABLE_SIZE evenly
    spaced points of 0..1, as (position, RGBA) stops of a Linear ramp."""
    last = RAMP_TABLE_SIZE - 1
    return tuple((i / last, tuple(ramp.evaluate(i / last))) for i in range(RAMP_TABLE_SIZE))


def _mix_inputs(node):
    """(factor, A, B) sockets of a Mix Color: MixRGB's three, or the Mix node's colour ones
    (Blender 3.4 on, which keeps a pair of sockets per data type)."""
    if node.type == "MIX_RGB":
        return node.inputs[0], node.inputs[1], node.inputs[2]
    by_id = {socket.identifier: socket for socket in node.inputs}
    kind = {"RGBA": "Color", "FLOAT": "Float", "VECTOR": "Vector"}.get(node.data_type, "Color")
    factor = by_id.get("Factor_Float") or node.inputs[0]
    return factor, by_id.get(f"A_{kind}", node.inputs[1]), by_id.get(f"B_{kind}", node.inputs[2])


def _number(socket) -> float:
    """A socket's own value as one number (a colour's mean)."""
    value = _constant(socket)
    return float(value if np.ndim(value) == 0 else np.mean(value))


def _constant(socket):
    """A socket's own value: a float, or the first three of a colour or vector."""
    value = getattr(socket, "default_value", 0.0)
    try:
        values = tuple(float(x) for x in value)
    except TypeError:
        return float(value)
    return values[:3] if len(values) >= 3 else (values + (0.0,) * 3)[:3]


def _shown(value) -> str:
    if np.ndim(value) == 0:
        return f"{float(value):g}"
    return ", ".join(f"{float(v):g}" for v in list(value)[:3])


def closure_kinds(surface) -> list[str]:
    """The closure kinds a graph renders with, for the material panel."""
    found, stack, seen = [], [surface], set()
    while stack:
        node = stack.pop()
        if node is None or id(node) in seen:
            continue
        seen.add(id(node))
        if node.kind not in ("mix_shader", "add_shader") and node.kind not in found:
            found.append(node.kind)
        for given in node.inputs.values():
            if isinstance(given, core.Link) and given.node.is_closure:
                stack.append(given.node)
    return found
