"""Materials and their textures: one row per distinct `Material`, all texture pixels in one
float32 array with an offset and size per texture (each `Texture` loaded once)."""

from __future__ import annotations

import numpy as np

from ..kernels.layout import Materials
from ..passes import crypto_id
from ..textures import load_texture
from .arrays import concatenated, rows


def pack_materials(shapes: list) -> tuple[Materials, dict[int, int]]:
    """The material table for these shapes, and each material's row by id()."""
    materials, row_of = [], {}
    for shape in shapes:
        if id(shape.material) not in row_of:
            row_of[id(shape.material)] = len(materials)
            materials.append((shape.material, shape.owner))
    textures, texture_of = [], {}
    for material, user in materials:
        texture = material.texture
        if texture is not None and id(texture) not in texture_of:
            texture_of[id(texture)] = len(textures)
            textures.append(load_texture(texture, f"material '{material.name}' (on {user})"))
    table = Materials(
        diffuse=rows([m.diffuse for m, _ in materials]),
        specular=rows([m.specular for m, _ in materials]),
        shininess=np.array([m.shininess for m, _ in materials], float),
        reflectivity=np.array([m.reflectivity for m, _ in materials], float),
        transparency=np.array([m.transparency for m, _ in materials], float),
        ior=rows([(m.outer_ior, m.inner_ior) for m, _ in materials], 2),
        texture=np.array([texture_of.get(id(m.texture), -1) for m, _ in materials], np.int32),
        texture_pixels=concatenated([t.reshape(-1, 3) for t in textures], (0, 3), np.float32),
        texture_offset=np.cumsum([0] + [t.shape[0] * t.shape[1] for t in textures])[:-1].astype(
            np.int64
        ),
        texture_size=np.array([(t.shape[1], t.shape[0]) for t in textures], np.int64).reshape(
            -1, 2
        ),
        pass_index=np.array([m.pass_index for m, _ in materials], np.int32),
        crypto=np.array([crypto_id(m.name) for m, _ in materials], np.float32),
        mirror=_pairs([(m.mirror_colour, _edge(m)) for m, _ in materials]),
        coat=rows([(m.coat, m.coat_ior, float(m.coat_hides)) for m, _ in materials]),
        glass_tint=_pairs([(m.glass_reflect, m.glass_transmit) for m, _ in materials]),
        refraction_fresnel=np.array([m.refraction_fresnel for m, _ in materials], float),
        mirror_hides_lights=np.array([not m.mirror_sees_lights for m, _ in materials], np.uint8),
        emission=rows([m.emission for m, _ in materials]),
        transparent=rows([m.transparent for m, _ in materials]),
        holdout=np.array([m.holdout for m, _ in materials], float),
    )
    return table, row_of


def _edge(material):
    """The mirror's tint at grazing incidence: its own tint when it has no Fresnel."""
    return material.mirror_colour if material.mirror_edge is None else material.mirror_edge


def _pairs(values: list) -> np.ndarray:
    """float64 (n, 2, 3) from n pairs of RGB triples."""
    return np.array(values, float).reshape(-1, 2, 3)
