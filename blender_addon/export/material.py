"""Blender materials into `core.Material`.

A material renders from its node tree, read as Cycles reads it from the active Material
Output down (shader_nodes; the mapping onto Whitted's model in shader_lobes and
principled), unless its Whitted panel says "Whitted Settings": then the panel's own values,
the report's material, count. A material without nodes renders its viewport colour as a
Lambert surface (Cycles' own fallback). What the tree holds that Whitted cannot honour is
one warning per material, naming it, the nodes and what was used instead.

Images are read from Blender's own pixels, so packed, generated and on-disk images all work.
"""

from __future__ import annotations

import numpy as np

from .. import core
from ..compat import node_tree_in_use
from .shader_lobes import Lobes
from .shader_nodes import MaterialReader

# The surface's share below which it is taken to be all glass (its lobes are divided by it)
SURFACE_CUTOFF = 1e-9


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
    settings = material.whitted
    if settings.use_whitted:
        return _whitted_settings(material)
    lobes, problems = read_lobes(material)
    if problems and warn is not None:
        warn(warning_text(material, problems))
    texture = None
    if lobes.texture is not None:
        texture = image_texture(lobes.texture, material.name)
    return from_lobes(lobes, material.name, material.pass_index, texture)


def read_lobes(material) -> tuple[Lobes, list[str]]:
    """The material's lobes from its node tree, and what could not be honoured."""
    tree = node_tree_in_use(material)
    if tree is None:
        lobes = Lobes()
        lobes.add_diffuse(1.0, tuple(material.diffuse_color[:3]))
        return lobes, []
    reader = MaterialReader(material)
    return reader.read(tree), reader.problems


def warning_text(material, problems: list[str]) -> str:
    return f"material '{material.name}': " + "; ".join(problems)


def from_lobes(lobes: Lobes, name: str, pass_index: int = 0, texture=None) -> core.Material:
    """The core material of weighted lobes: the glass's weight is the transparency, the
    other lobes are shares of the rest (the integrator scales them by 1 - transparency)."""
    glass = min(lobes.glass, 1.0)
    surface = 1.0 - glass
    per_surface = 1.0 / surface if surface > SURFACE_CUTOFF else 0.0
    mirror_normal = lobes.mirror_normal * per_surface
    mirror_edge = lobes.mirror_edge * per_surface
    mirrors = bool(np.any(mirror_normal > 0.0) or np.any(mirror_edge > 0.0))
    ks = lobes.highlight * per_surface
    shininess = lobes.shininess_sum / lobes.highlight.mean() if np.any(ks > 0.0) else 1.0
    per_glass = 1.0 / lobes.glass if lobes.glass > 0.0 else 0.0
    return core.Material(
        diffuse=_triple(lobes.diffuse * per_surface),
        specular=_triple(ks),
        shininess=float(shininess),
        name=name,
        reflectivity=1.0 if mirrors else 0.0,
        transparency=glass,
        outer_ior=1.0,
        inner_ior=lobes.glass_ior_sum * per_glass if lobes.glass > 0.0 else 1.0,
        texture=texture,
        pass_index=pass_index,
        mirror_colour=_triple(mirror_normal) if mirrors else (1.0, 1.0, 1.0),
        mirror_edge=_triple(mirror_edge) if mirrors else None,
        mirror_sees_lights=not lobes.rough_mirror,
        coat=min(lobes.coat * per_surface, 1.0),
        coat_ior=lobes.coat_ior_sum / lobes.coat if lobes.coat > 0.0 else 1.5,
        coat_hides=lobes.coat_hides,
        glass_reflect=_triple(lobes.glass_reflect * per_glass) if glass else (1.0, 1.0, 1.0),
        glass_transmit=_triple(lobes.glass_transmit * per_glass) if glass else (1.0, 1.0, 1.0),
        refraction_fresnel=lobes.refraction_fresnel_sum * per_glass if glass else 1.0,
        emission=_triple(lobes.emission),
        transparent=_triple(np.clip(lobes.transparent, 0.0, 1.0)),
        holdout=min(lobes.holdout, 1.0),
    )


def _triple(values) -> tuple[float, float, float]:
    return tuple(float(v) for v in np.maximum(values, 0.0)[:3])


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
    pixels = pixels.reshape(height, width, image.channels)[::-1, :, :3]
    if image.channels < 3:
        pixels = np.repeat(pixels[..., :1], 3, axis=2)
    linear = image.colorspace_settings.name in {"Non-Color", "Linear", "Linear Rec.709"}
    # Float images hold linear values whatever their colour space says
    srgb = not linear and not image.is_float
    return core.Texture(pixels=np.ascontiguousarray(pixels), srgb=srgb)
