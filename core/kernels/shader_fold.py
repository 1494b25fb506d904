"""Folding a constant shader program at compile time: run once, its Surface written out
as numbers, so that the material table holds it and the kernels run nothing per hit."""

import numpy as np

from ..jit.decorators import allocating_kernel, kernel
from .shader_program import LOBE_COUNT, SHADER_STACK, run_program
from .surface_terms import (
    CLEAR_COAT_COLUMNS,
    GLOSS_COLUMNS,
    clear_coat_columns,
    gloss_columns,
    terms_from_lobes,
)

# The columns of a folded row (fold_surfaces' out), in Surface's order
FOLDED_COLUMNS = 36 + GLOSS_COLUMNS + CLEAR_COAT_COLUMNS + 10


@kernel
def _three(o, first, v):
    o[first], o[first + 1], o[first + 2] = v[0], v[1], v[2]


@allocating_kernel
def fold_surfaces(mats, rows, out):
    """Run the programs of material `rows` at a hit that reads nothing, writing each Surface
    to a row of `out` (FOLDED_COLUMNS: kd, ks, shininess, reflectivity, transparency, outer
    and inner IOR, mirror normal and edge, hides lights, coat, coat IOR, coat hides, glass
    reflect and transmit, refraction Fresnel, emission, transparent, holdout, roughness,
    gloss, clear coat, coat tint, mirror dip, translucent, diffuse roughness)."""
    stack = np.zeros(SHADER_STACK)
    lobes = np.zeros(LOBE_COUNT)
    zero = (0.0, 0.0, 0.0)
    here = (zero, zero, zero, zero)
    rows3 = ((1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0))
    for k in range(rows.shape[0]):
        # (A program that reads the ray is varying, never folded: the ray here is nobody's)
        nobody = (0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0,
                  0.0, 0.0, 0.0, 0.0, 0.0, 0.0)  # fmt: skip
        run_program(
            mats, rows[k], stack, lobes, (here, here, here), (zero, zero, zero), rows3, nobody
        )
        s = terms_from_lobes(lobes)
        o = out[k]
        _three(o, 0, s.kd)
        _three(o, 3, s.ks)
        o[6], o[7], o[8] = s.shininess, s.reflectivity, s.transparency
        o[9], o[10] = s.outer_ior, s.inner_ior
        _three(o, 11, s.mirror_normal)
        _three(o, 14, s.mirror_edge)
        o[17] = 1.0 if s.mirror_hides_lights else 0.0
        o[18], o[19], o[20] = s.coat, s.coat_ior, 1.0 if s.coat_hides else 0.0
        _three(o, 21, s.glass_reflect)
        _three(o, 24, s.glass_transmit)
        o[27] = s.refraction_fresnel
        _three(o, 28, s.emission)
        _three(o, 31, s.transparent)
        o[34] = s.holdout
        o[35] = s.roughness
        gloss_columns(s.gloss, o, 36)
        clear_coat_columns(s.clear_coat, o, 36 + GLOSS_COLUMNS)
        _three(o, 36 + GLOSS_COLUMNS + CLEAR_COAT_COLUMNS, s.coat_tint)
        _three(o, 39 + GLOSS_COLUMNS + CLEAR_COAT_COLUMNS, s.mirror_dip)
        _three(o, 42 + GLOSS_COLUMNS + CLEAR_COAT_COLUMNS, s.translucent)
        o[45 + GLOSS_COLUMNS + CLEAR_COAT_COLUMNS] = s.diffuse_roughness
