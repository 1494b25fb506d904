"""Blender materials into `core.Material`.

A material renders from its Principled BSDF unless its Whitted panel says "Whitted
settings" (then the panel's own values count). From the Principled BSDF:

    diffuse       base colour x (1 - metallic) x (1 - transmission)
    specular      0.04 grey for dielectrics, the base colour for metals (mixed by metallic),
                  scaled by (1 - roughness)
    shininess     2 / roughness^4 - 2, the Phong exponent of a Beckmann lobe of that
                  roughness (Walter et al. 2007), at most 10,000
    reflectivity  metallic x (1 - roughness): smooth metals are mirrors
    transparency  transmission; inner IOR the BSDF's IOR, outer 1
    texture       an Image Texture node feeding Base Color

In both cases an Image Texture node linked to the base colour (or the panel's image)
replaces the diffuse colour. Images are read from Blender's own pixels, so packed, generated
and on-disk images all work.
"""

from __future__ import annotations

import numpy as np

from .. import core
from ..compat import TRANSMISSION_INPUTS, node_tree_in_use

MAX_SHININESS = 10000.0


def find_node(datablock, node_type):
    tree = node_tree_in_use(datablock)
    if tree is None:
        return None
    return next((node for node in tree.nodes if node.type == node_type), None)


def _input(node, *names, default=0.0):
    """A node input's value by the first name that exists (names changed across versions)."""
    for name in names:
        socket = node.inputs.get(name)
        if socket is not None:
            return socket.default_value
    return default


def convert(material) -> core.Material:
    if material is None:
        return core.Material(name="(no material)")
    settings = material.whitted
    principled = find_node(material, "BSDF_PRINCIPLED")
    image = settings.image if settings.use_whitted else _base_colour_image(principled)
    texture = None if image is None else image_texture(image, material.name)
    if settings.use_whitted or principled is None:
        base = _base_colour(material, principled)
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
    base = np.array(_base_colour(material, principled))
    metallic = float(_input(principled, "Metallic"))
    roughness = float(_input(principled, "Roughness", default=0.5))
    transmission = float(_input(principled, *TRANSMISSION_INPUTS))
    ior = float(_input(principled, "IOR", default=1.45))
    specular = (0.04 * (1.0 - metallic) + base * metallic) * (1.0 - roughness)
    shininess = MAX_SHININESS if roughness <= 0.0 else 2.0 / roughness**4 - 2.0
    return core.Material(
        diffuse=tuple(base * (1.0 - metallic) * (1.0 - transmission)),
        specular=tuple(specular),
        shininess=float(min(max(shininess, 0.0), MAX_SHININESS)),
        name=material.name,
        reflectivity=metallic * (1.0 - roughness),
        transparency=transmission,
        outer_ior=1.0,
        inner_ior=ior if ior > 0.0 else 1.0,
        texture=texture,
        pass_index=material.pass_index,
    )


def _base_colour(material, principled) -> tuple[float, float, float]:
    if principled is not None:
        return tuple(float(c) for c in _input(principled, "Base Color")[:3])
    return tuple(float(c) for c in material.diffuse_color[:3])


def _base_colour_image(principled):
    if principled is None:
        return None
    socket = principled.inputs.get("Base Color")
    if socket is None or not socket.is_linked:
        return None
    node = socket.links[0].from_node
    return node.image if node.type == "TEX_IMAGE" else None


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
