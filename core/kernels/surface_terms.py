"""What a hit's material is, in the integrator's terms (`Surface`): read from the material
table, or made from the lobes its shader program added up at the hit (`terms_from_lobes`,
the same rule core.compile.shader_program folds constant programs with)."""

import math
from typing import NamedTuple

from ..jit.decorators import kernel
from .microfacet import Gloss
from .shader_program import (
    L_CLEAR,
    L_CLEAR_AT_NORMAL,
    L_CLEAR_COVER,
    L_CLEAR_IOR,
    L_CLEAR_NORMAL,
    L_CLEAR_NORMAL_WEIGHT,
    L_CLEAR_ROUGHNESS,
    L_CLEAR_TINT,
    L_COAT,
    L_COAT_HIDES,
    L_COAT_IOR,
    L_COAT_TINT,
    L_DIFFUSE,
    L_DIFFUSE_ROUGHNESS,
    L_DIFFUSE_ROUGHNESS_WEIGHT,
    L_DIP,
    L_EDGE,
    L_EMISSION,
    L_FRESNEL,
    L_GLASS,
    L_GLASS_IOR,
    L_GLASS_REFLECT,
    L_GLASS_TRANSMIT,
    L_GLOSS_ALPHA,
    L_GLOSS_BECKMANN,
    L_GLOSS_COAT,
    L_GLOSS_COAT_IOR,
    L_GLOSS_COAT_MS,
    L_GLOSS_COAT_TINT,
    L_GLOSS_DIP,
    L_GLOSS_EDGE,
    L_GLOSS_MS_EDGE,
    L_GLOSS_MS_NORMAL,
    L_GLOSS_NORMAL,
    L_GLOSS_WEIGHT,
    L_HOLDOUT,
    L_MIRROR,
    L_NORMAL,
    L_NORMAL_WEIGHT,
    L_ROUGH,
    L_ROUGHNESS,
    L_ROUGHNESS_WEIGHT,
    L_TRANSLUCENT,
    L_TRANSPARENT,
)
from .vec import row

# The surface's share below which a material is all glass (its lobes are divided by it)
SURFACE_CUTOFF = 1e-9


class ClearCoat(NamedTuple):
    """A clear layer over the whole surface (the Principled BSDF's Coat, Blender 4.0 on):
    it reflects as a dielectric of its own IOR, roughness and normal, and what lies below it
    is dimmed by what it reflects and tinted by what it absorbs (core.kernels.clear_coat)."""

    weight: float  # its reflection's weight (the Coat Weight times the closure's share)
    layer: float  # the Coat Weight of the closures it covers: what dims the layers below
    ior: float
    roughness: float  # 0 sharp; past SHARP_ROUGHNESS it glints in Blender's lights
    tint: tuple  # RGB at normal incidence (Coat Tint)
    normal: tuple  # world, unit, or zero: the surface's own smooth normal
    at_normal: bool  # dims by the Fresnel at its normal (Blender 4.2), else its lobe's mean


# Materials.clear_coat's columns: ClearCoat's fields, its triples as three
CLEAR_COAT_COLUMNS = 11
NO_CLEAR_COAT = ClearCoat(0.0, 0.0, 1.5, 0.0, (1.0, 1.0, 1.0), (0.0, 0.0, 0.0), False)


class Surface(NamedTuple):
    """A material at one hit (core.model.Material names the terms)."""

    kd: tuple
    ks: tuple
    shininess: float
    reflectivity: float
    transparency: float
    outer_ior: float
    inner_ior: float
    mirror_normal: tuple
    mirror_edge: tuple
    mirror_hides_lights: bool
    coat: float
    coat_ior: float
    coat_hides: bool
    glass_reflect: tuple
    glass_transmit: tuple
    refraction_fresnel: float
    emission: tuple
    transparent: tuple
    holdout: float
    normal: tuple  # the shading normal its graph gives (world), or zero: the surface's own
    roughness: float  # its mirror's and glass's, 0 sharp (blurred when glossy rays are sampled)
    gloss: Gloss  # its rough lobes' glints (core.kernels.microfacet); alpha 0: none
    clear_coat: ClearCoat  # weight 0: none
    coat_tint: tuple  # the coat's Specular Tint (RGB; microfacet.tinted_fresnel), white: none
    mirror_dip: tuple  # F82's dip below the mirror's Schlick curve (microfacet.f82_dip)
    translucent: tuple  # RGB Lambertian transmission (core.kernels.translucent)
    diffuse_roughness: float  # the diffuse's Oren-Nayar roughness (core.kernels.rough_diffuse)


# Materials.gloss's columns: Gloss's fields, its triples as three
GLOSS_COLUMNS = 23


@kernel
def _gloss_row(table, material):
    g = table[material]
    return Gloss(
        g[0], g[1] != 0.0, (g[2], g[3], g[4]), (g[5], g[6], g[7]), (g[8], g[9], g[10]),
        (g[11], g[12], g[13]), g[14], g[15], g[16], (g[17], g[18], g[19]),
        (g[20], g[21], g[22]),
    )  # fmt: skip


@kernel
def gloss_columns(gloss, o, first):
    """Write a Gloss to o[first : first + GLOSS_COLUMNS] (the inverse of _gloss_row)."""
    o[first], o[first + 1] = gloss.alpha, 1.0 if gloss.beckmann else 0.0
    for c in range(3):
        o[first + 2 + c] = gloss.normal[c]
        o[first + 5 + c] = gloss.edge[c]
        o[first + 8 + c] = gloss.ms_normal[c]
        o[first + 11 + c] = gloss.ms_edge[c]
    o[first + 14], o[first + 15], o[first + 16] = gloss.coat, gloss.coat_ior, gloss.coat_ms
    for c in range(3):
        o[first + 17 + c] = gloss.coat_tint[c]
        o[first + 20 + c] = gloss.dip[c]


@kernel
def _clear_coat_row(table, material):
    c = table[material]
    return ClearCoat(c[0], c[1], c[2], c[3], (c[4], c[5], c[6]), (c[7], c[8], c[9]), c[10] != 0.0)


@kernel
def clear_coat_columns(coat, o, first):
    """Write a ClearCoat to o[first : first + CLEAR_COAT_COLUMNS] (the inverse of
    _clear_coat_row)."""
    o[first], o[first + 1], o[first + 2], o[first + 3] = (
        coat.weight,
        coat.layer,
        coat.ior,
        coat.roughness,
    )
    for c in range(3):
        o[first + 4 + c] = coat.tint[c]
        o[first + 7 + c] = coat.normal[c]
    o[first + 10] = 1.0 if coat.at_normal else 0.0


@kernel
def _pair(table, material, which):
    return (
        table[material, which, 0],
        table[material, which, 1],
        table[material, which, 2],
    )


@kernel
def table_surface(mats, material, kd):
    """The material's row of the table, with its diffuse colour kd (its texture's at the
    hit, or its own)."""
    return Surface(
        kd,
        row(mats.specular, material),
        mats.shininess[material],
        mats.reflectivity[material],
        mats.transparency[material],
        mats.ior[material, 0],
        mats.ior[material, 1],
        _pair(mats.mirror, material, 0),
        _pair(mats.mirror, material, 1),
        mats.mirror_hides_lights[material] != 0,
        mats.coat[material, 0],
        mats.coat[material, 1],
        mats.coat[material, 2] != 0.0,
        _pair(mats.glass_tint, material, 0),
        _pair(mats.glass_tint, material, 1),
        mats.refraction_fresnel[material],
        row(mats.emission, material),
        row(mats.transparent, material),
        mats.holdout[material],
        (0.0, 0.0, 0.0),
        mats.roughness[material],
        _gloss_row(mats.gloss, material),
        _clear_coat_row(mats.clear_coat, material),
        (mats.coat[material, 3], mats.coat[material, 4], mats.coat[material, 5]),
        row(mats.mirror_dip, material),
        row(mats.translucent, material),
        mats.diffuse_roughness[material],
    )


@kernel
def _scaled(lobes, slot, factor):
    return (
        max(lobes[slot] * factor, 0.0),
        max(lobes[slot + 1] * factor, 0.0),
        max(lobes[slot + 2] * factor, 0.0),
    )


@kernel
def terms_from_lobes(lobes):
    """The Surface the lobes make: the glass's weight is the transparency, the other lobes
    are shares of the rest (the integrator scales them by 1 - transparency)."""
    glass = min(lobes[L_GLASS], 1.0)
    rest = 1.0 - glass
    per_rest = 1.0 / rest if rest > SURFACE_CUTOFF else 0.0
    per_glass = 1.0 / lobes[L_GLASS] if lobes[L_GLASS] > 0.0 else 0.0
    mirror_normal = _scaled(lobes, L_MIRROR, per_rest)
    mirror_edge = _scaled(lobes, L_EDGE, per_rest)
    mirrors = max(mirror_normal) > 0.0 or max(mirror_edge) > 0.0
    coat = lobes[L_COAT]
    white = (1.0, 1.0, 1.0)
    return Surface(
        _scaled(lobes, L_DIFFUSE, per_rest),
        (0.0, 0.0, 0.0),  # no Phong highlight: the rough lobes glint (gloss)
        1.0,
        1.0 if mirrors else 0.0,
        glass,
        1.0,
        lobes[L_GLASS_IOR] * per_glass if glass > 0.0 else 1.0,
        mirror_normal if mirrors else white,
        mirror_edge if mirrors else white,
        lobes[L_ROUGH] != 0.0,
        min(coat * per_rest, 1.0),
        lobes[L_COAT_IOR] / coat if coat > 0.0 else 1.5,
        lobes[L_COAT_HIDES] != 0.0,
        _scaled(lobes, L_GLASS_REFLECT, per_glass) if glass > 0.0 else white,
        _scaled(lobes, L_GLASS_TRANSMIT, per_glass) if glass > 0.0 else white,
        lobes[L_FRESNEL] * per_glass if glass > 0.0 else 1.0,
        _scaled(lobes, L_EMISSION, 1.0),
        (
            min(max(lobes[L_TRANSPARENT], 0.0), 1.0),
            min(max(lobes[L_TRANSPARENT + 1], 0.0), 1.0),
            min(max(lobes[L_TRANSPARENT + 2], 0.0), 1.0),
        ),
        min(lobes[L_HOLDOUT], 1.0),
        _normal(lobes),
        _mean_roughness(lobes),
        _gloss(lobes, per_rest),
        _clear_coat(lobes),
        _mean_tint(lobes, L_COAT_TINT, coat),
        _scaled(lobes, L_DIP, per_rest) if mirrors else (0.0, 0.0, 0.0),
        _scaled(lobes, L_TRANSLUCENT, per_rest),
        _mean_diffuse_roughness(lobes),
    )


@kernel
def _mean_diffuse_roughness(lobes):
    """The diffuse closures' roughness, weighted by their weights (one Oren-Nayar lobe
    stands for a mix of them)."""
    weight = lobes[L_DIFFUSE_ROUGHNESS_WEIGHT]
    return min(max(lobes[L_DIFFUSE_ROUGHNESS] / weight, 0.0), 1.0) if weight > 0.0 else 0.0


@kernel
def _gloss(lobes, per_rest):
    """The rough lobes' glints as shares of the rest (as the other lobes are)."""
    weight = lobes[L_GLOSS_WEIGHT]
    if weight <= 0.0:
        return Gloss(0.0, False, (0.0, 0.0, 0.0), (0.0, 0.0, 0.0), (0.0, 0.0, 0.0),
                     (0.0, 0.0, 0.0), 0.0, 1.5, 0.0, (1.0, 1.0, 1.0),
                     (0.0, 0.0, 0.0))  # fmt: skip
    coat = lobes[L_GLOSS_COAT]
    return Gloss(
        lobes[L_GLOSS_ALPHA] / weight,
        lobes[L_GLOSS_BECKMANN] > 0.5 * weight,  # the distribution of most of the lobes
        _scaled(lobes, L_GLOSS_NORMAL, per_rest),
        _scaled(lobes, L_GLOSS_EDGE, per_rest),
        _scaled(lobes, L_GLOSS_MS_NORMAL, per_rest),
        _scaled(lobes, L_GLOSS_MS_EDGE, per_rest),
        coat * per_rest,
        lobes[L_GLOSS_COAT_IOR] / coat if coat > 0.0 else 1.5,
        lobes[L_GLOSS_COAT_MS] * per_rest,
        _mean_tint(lobes, L_GLOSS_COAT_TINT, coat),
        _scaled(lobes, L_GLOSS_DIP, per_rest),
    )


@kernel
def _mean_tint(lobes, slot, weight):
    """The weighted mean of the tints summed in `slot` (white if none)."""
    if weight <= 0.0:
        return 1.0, 1.0, 1.0
    return _scaled(lobes, slot, 1.0 / weight)


@kernel
def _clear_coat(lobes):
    """The clear coats' weighted means (their weight, not shares of the rest: the coat lies
    over the glass too)."""
    weight = lobes[L_CLEAR]
    if weight <= 0.0:
        return NO_CLEAR_COAT
    per = 1.0 / weight
    return ClearCoat(
        weight,
        weight / lobes[L_CLEAR_COVER],
        lobes[L_CLEAR_IOR] * per,
        lobes[L_CLEAR_ROUGHNESS] * per,
        _scaled(lobes, L_CLEAR_TINT, per),
        _unit_or_zero(lobes, L_CLEAR_NORMAL, L_CLEAR_NORMAL_WEIGHT),
        lobes[L_CLEAR_AT_NORMAL] > 0.5 * weight,  # the rule of most of the coats
    )


@kernel
def _mean_roughness(lobes):
    """The mirror, coat and glass lobes' roughness, weighted by the lobes' weights."""
    weight = lobes[L_ROUGHNESS_WEIGHT]
    return min(max(lobes[L_ROUGHNESS] / weight, 0.0), 1.0) if weight > 0.0 else 0.0


@kernel
def _normal(lobes):
    """The weighted mean of the Normal inputs the closures were given, unit, or zero."""
    return _unit_or_zero(lobes, L_NORMAL, L_NORMAL_WEIGHT)


@kernel
def _unit_or_zero(lobes, slot, weight_slot):
    if lobes[weight_slot] <= 0.0:
        return 0.0, 0.0, 0.0
    n = (lobes[slot], lobes[slot + 1], lobes[slot + 2])
    length = math.sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2])
    if length == 0.0:
        return 0.0, 0.0, 0.0
    return n[0] / length, n[1] / length, n[2] / length
