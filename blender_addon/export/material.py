"""Blender materials into `core.Material`.

A material renders from its node tree, read as Cycles reads it from the active Material
Output down into a core shader graph (shader_nodes), which the kernels run per hit or the
compile folds into numbers (core.kernels.shader_program has the mapping onto Whitted's model),
unless its Whitted panel says "Whitted Settings": then the panel's own values, the report's
material, count. A material without nodes renders its viewport colour as a Lambert surface
(Cycles' own fallback). What the tree holds that Whitted cannot honour is one warning per
material, naming it, the nodes and what was used instead.

Images are read from Blender's own pixels, so packed, generated and on-disk images all work.
"""

from __future__ import annotations

import numpy as np

from .. import core
from ..compat import node_tree_in_use
from .shader_nodes import GraphReader


def find_node(datablock, node_type):
    tree = node_tree_in_use(datablock)
    if tree is None:
        return None
    return next((node for node in tree.nodes if node.type == node_type), None)


def convert(material, warn=None) -> core.Material:
    """The core material of a Blender material (None: Blender's default grey surface);
    `warn(text)` gets the one warning of what its tree holds that Whitted cannot honour."""
    if material is None:
        return core.Material(name="(no material)")
    if material.whitted.use_whitted:
        return _whitted_settings(material)
    reader = _reader(material)
    surface = reader.read(node_tree_in_use(material)) if reader is not None else None
    problems = reader.problems if reader is not None else []
    if problems and warn is not None:
        warn(warning_text(material, problems))
    if surface is None:
        lambert = tuple(float(c) for c in material.diffuse_color[:3])
        tree = node_tree_in_use(material)
        colour = lambert if tree is None else (0.0, 0.0, 0.0)  # nothing linked: black
        return core.Material(diffuse=colour, name=material.name, pass_index=material.pass_index)
    return core.Material(name=material.name, pass_index=material.pass_index, surface=surface,
                         emission_lights=emission_lights(material),
                         absorption=reader.absorption,
                         bump_rule=bump_rule(material, reader.displaced is not None))  # fmt: skip


def bump_rule(material, displaced: bool) -> str:
    """core.Material.bump_rule: "displaced" where the Material Output's Displacement bends
    the normal (Cycles makes it the surface's own: no shadow terminator term), else
    Material › Settings › Bump Map Correction's "corrected" or "uncorrected"."""
    if displaced:
        return "displaced"
    cycles = getattr(material, "cycles", None)
    corrected = getattr(cycles, "use_bump_map_correction", True) if cycles is not None else True
    return "corrected" if corrected else "uncorrected"


def emission_lights(material) -> bool:
    """Whitted Material › Emission Lights: Auto follows Cycles' Emission Sampling (Blender
    4.0 on) or Multiple Importance (before): lights unless it is None or off."""
    choice = material.whitted.emission_lights
    if choice != "AUTO":
        return choice == "ON"
    cycles = getattr(material, "cycles", None)
    if cycles is None:
        return True
    if hasattr(cycles, "emission_sampling"):
        return cycles.emission_sampling != "NONE"
    return bool(getattr(cycles, "sample_as_light", True))


def read_graph(material, textures: bool = True):
    """(core closure node or None, what could not be honoured, the absorption of the medium
    it encloses) of the material's tree. Without `textures`, images are not read (the
    panel's quick look)."""
    reader = _reader(material, textures)
    if reader is None:
        return None, [], (0.0, 0.0, 0.0)
    return reader.read(node_tree_in_use(material)), reader.problems, reader.absorption


def _reader(material, textures: bool = True) -> GraphReader | None:
    """A reader of the material's tree (None: no nodes), each image one core Texture."""
    if node_tree_in_use(material) is None:
        return None
    owner = f"material '{material.name}'"
    made: dict = {}  # one core Texture per image, however many nodes show it

    def make(image):
        if image.as_pointer() not in made:
            texture = image_texture(image, owner=owner) if textures else _placeholder(image)
            made[image.as_pointer()] = texture
        return made[image.as_pointer()]

    return GraphReader(material, make)


def _placeholder(image):
    return core.Texture(pixels=np.zeros((1, 1, 4)), srgb=False, name=image.name)


def warning_text(material, problems: list[str]) -> str:
    return f"material '{material.name}': " + "; ".join(problems)


def _whitted_settings(material) -> core.Material:
    """The report's material, from the Whitted Material panel."""
    settings = material.whitted
    texture = None if settings.image is None else image_texture(settings.image, material.name)
    principled = find_node(material, "BSDF_PRINCIPLED")
    if principled is not None:
        base = tuple(float(c) for c in principled.inputs["Base Color"].default_value[:3])
    else:
        base = tuple(float(c) for c in material.diffuse_color[:3])
    return core.Material(
        diffuse=base,
        specular=tuple(settings.specular),
        shininess=settings.shininess,
        name=material.name,
        reflectivity=settings.reflectivity,
        transparency=settings.transparency,
        outer_ior=settings.outer_ior,
        inner_ior=settings.inner_ior,
        texture=texture,
        pass_index=material.pass_index,
    )


def image_texture(image, material_name: str = "", owner: str = "") -> core.Texture:
    """The image's pixels, top row first, as a core texture; sRGB unless Blender says the
    image holds linear (non-colour) data. Errors name `owner`, or the material."""
    owner = owner or f"material '{material_name}'"
    # Reading the pixels loads an on-disk image not read yet (has_data stays False until
    # then in Blender 3.4); a missing or unreadable file gives none
    count = len(image.pixels)
    if count == 0 or 0 in tuple(image.size):
        raise core.SceneError(
            owner,
            f"image '{image.name}'",
            f"has no pixels (file '{image.filepath}' missing or unreadable); reload or "
            "replace the image in its Image or Environment Texture node, or the Whitted "
            "Material panel",
        )
    width, height = image.size
    pixels = np.empty(width * height * image.channels, np.float32)
    image.pixels.foreach_get(pixels)
    pixels = pixels.reshape(height, width, image.channels)[::-1]
    if image.channels < 3:  # grey (and alpha): as RGB(A)
        grey = np.repeat(pixels[..., :1], 3, axis=2)
        pixels = np.concatenate([grey, pixels[..., 1:2]], axis=2) if image.channels == 2 else grey
    pixels = pixels[..., :4]  # RGB, and alpha when the image has it
    linear = image.colorspace_settings.name in {"Non-Color", "Linear", "Linear Rec.709"}
    # Float images hold linear values whatever their colour space says
    srgb = not linear and not image.is_float
    return core.Texture(pixels=np.ascontiguousarray(pixels), srgb=srgb)
