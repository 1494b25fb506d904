"""The Principled BSDF in Whitted's lobes (shader_lobes), as each Blender's Cycles builds it.

Blender 4.0 on (Cycles' layered Principled), with weight w, base colour B, metallic m,
transmission t, alpha a:

    transparent   w (1 - a);  then w = w a
    emission      w x Emission Color x Emission Strength
    metal         mirror of weight w m, tint B at normal incidence, white at grazing (F82
                  Tint with a white Specular Tint is Schlick's); then w = w (1 - m)
    glass         weight w t, its IOR, reflection tinted by Specular Tint, each crossing by
                  sqrt(B) (so that passing through a solid tints by B); then w = w (1 - t)
    specular      a coat of weight w with the IOR that Specular IOR Level makes of IOR
                  (F0 = F0(IOR) x 2 level), dimming the diffuse below it
    diffuse       w B

Before 4.0 (Cycles' additive Principled): the diffuse is B (1 - m)(1 - t); the specular
lobe (weight 1 - t (1 - m)) is a metal mirror of weight m (tint B to white) and a coat of
weight 1 - m with F0 = 0.08 Specular, not dimming the diffuse; glass of weight t (1 - m)
reflects white (towards B by Specular Tint) and tints each crossing by B.
"""

from __future__ import annotations

import numpy as np

from .shader_graph import node_label
from .shader_lobes import Lobes, f0_of_ior, ior_of_f0

WEIGHT_CUTOFF = 1e-5

# Inputs that change the look but are not modelled, with the value that changes nothing
_UNMODELLED = (
    ("Coat Weight", 0.0, "no coat"),
    ("Clearcoat", 0.0, "no clearcoat"),
    ("Sheen Weight", 0.0, "no sheen"),
    ("Sheen", 0.0, "no sheen"),
    ("Subsurface Weight", 0.0, "the base colour as diffuse"),
    ("Subsurface", 0.0, "the base colour as diffuse"),
    ("Anisotropic", 0.0, "isotropic"),
    ("Thin Film Thickness", 0.0, "no thin film"),
    ("Diffuse Roughness", 0.0, "Lambert"),
)


def principled_lobes(reader, node, groups, weight: float, layered: bool) -> Lobes:
    lobes = Lobes()
    for name, neutral, used in _UNMODELLED:
        socket = node.inputs.get(name)
        if socket is not None and reader.number(node, groups, name) != neutral:
            reader.note(f"{node_label(node)}'s {name} is not modelled (used: {used})")
    for name in ("Normal", "Coat Normal", "Clearcoat Normal", "Tangent"):
        reader.linked(node, groups, name, "the surface's own normal")
    base, image = reader.colour(node, groups, "Base Color", textures=True)
    base = np.clip(base, 0.0, None)
    clamped = np.minimum(base, 1.0)
    roughness = min(max(reader.number(node, groups, "Roughness", default=0.5), 0.0), 1.0)
    metallic = min(max(reader.number(node, groups, "Metallic"), 0.0), 1.0)
    transmission = min(
        max(reader.number(node, groups, "Transmission Weight", "Transmission"), 0.0), 1.0
    )
    ior = max(reader.number(node, groups, "IOR", default=1.45), 1e-5)
    alpha = min(max(reader.number(node, groups, "Alpha", default=1.0), 0.0), 1.0)
    lobes.transparent += weight * (1.0 - alpha)
    weight *= alpha
    emission, _ = reader.colour(node, groups, "Emission Color", "Emission")
    strength = reader.number(node, groups, "Emission Strength", default=1.0)
    lobes.emission += weight * np.maximum(emission * strength, 0.0)
    if layered:
        _layered(reader, node, groups, lobes, weight, base, clamped, image, roughness,
                 metallic, transmission, ior)  # fmt: skip
    else:
        _additive(reader, node, groups, lobes, weight, base, clamped, image, roughness,
                  metallic, transmission, ior)  # fmt: skip
    return lobes


def _layered(reader, node, groups, lobes, w, base, clamped, image, roughness, metallic,
             transmission, ior):  # fmt: skip
    tint, _ = reader.colour(node, groups, "Specular Tint")
    tint = np.clip(tint, 0.0, None)
    if metallic > WEIGHT_CUTOFF:
        lobes.add_mirror(w * metallic, clamped, np.ones(3), roughness)
        w *= 1.0 - metallic
    if transmission > WEIGHT_CUTOFF:
        lobes.add_glass(w * transmission, ior, tint, np.sqrt(clamped))
        w *= 1.0 - transmission
    level = max(reader.number(node, groups, "Specular IOR Level", default=0.5), 0.0)
    f0 = f0_of_ior(ior) * 2.0 * level
    if f0 > 0.0 and w > WEIGHT_CUTOFF:
        if not np.allclose(tint, 1.0):
            reader.note(f"{node_label(node)}'s Specular Tint on a dielectric (used: white)")
        lobes.add_coat(w, ior_of_f0(f0), roughness, hides=True)
    lobes.add_diffuse(w, base, image)


def _additive(reader, node, groups, lobes, w, base, clamped, image, roughness, metallic,
              transmission, ior):  # fmt: skip
    specular = max(reader.number(node, groups, "Specular", default=0.5), 0.0)
    specular_tint = min(max(reader.number(node, groups, "Specular Tint"), 0.0), 1.0)
    glass = transmission * (1.0 - metallic)
    lobes.add_diffuse(w * (1.0 - metallic) * (1.0 - transmission), base, image)
    spec_weight = w * (1.0 - glass)
    if metallic > WEIGHT_CUTOFF:
        lobes.add_mirror(spec_weight * metallic, clamped, np.ones(3), roughness)
    if specular > 0.0 and metallic < 1.0:
        lobes.add_coat(spec_weight * (1.0 - metallic), ior_of_f0(0.08 * specular), roughness,
                       hides=False)  # fmt: skip
    if glass > WEIGHT_CUTOFF:
        reflect = (1.0 - specular_tint) + clamped * specular_tint
        lobes.add_glass(w * glass, ior, reflect, clamped)
