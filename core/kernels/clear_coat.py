"""A clear coat over a whole surface (the Principled BSDF's Coat, Blender 4.0 on), layered as
Cycles layers it.

At a hit seen along unit d, with the coat's unit normal n_c facing the viewer (its Coat
Normal, or else the surface's own smooth normal: a normal map on the layers below leaves
the coat smooth, as in Cycles) and cos = n_c . (-d):

    the coat reflects          w F(cos)        F the exact Fresnel of its IOR (a rough
                                               coat: the mean over its GGX lobe, F_mean,
                                               as Cycles from 4.5; 4.2 keeps F at n_c)
    the layers below, times    under = max(0, 1 - c F) (1 + c (tint^(1 / cos_t) - 1))

with w its reflection's weight (ClearCoat.weight), c its Coat Weight (ClearCoat.layer) and
cos_t the cosine of the view ray refracted into the coat: its tint is the colour at normal
incidence, and a slanted ray crosses more of it (Beer-Lambert over a path 1 / cos_t). Both
factors are Cycles' (its layering weight 1 - albedo, and its Coat Tint), and as in Cycles
they are taken for the viewing direction only: what lies below is dimmed alike for every
light. A rough coat (past SHARP_ROUGHNESS) also glints in Blender's lights, as a GGX
dielectric lobe (core.kernels.microfacet.gloss_lit); a sharp one is a mirror, in which the
lights are seen.
"""

import math

from ..jit.decorators import kernel
from .bent_normal import kept_above
from .fresnel import fresnel_dielectric
from .microfacet import Gloss, dielectric_fresnel_mean
from .shader_program import SHARP_ROUGHNESS
from .vec import dot, scale

ZERO3 = (0.0, 0.0, 0.0)
NO_GLINT = Gloss(0.0, False, ZERO3, ZERO3, ZERO3, ZERO3, 0.0, 1.5, 0.0, (1.0, 1.0, 1.0), ZERO3)


@kernel
def coat_normal(coat, d, n_geometric, n_smooth):
    """The coat's unit normal facing the viewer (n_geometric and n_smooth do), kept from
    reflecting the ray below the surface as a bent shading normal is."""
    n = coat.normal
    if n[0] == 0.0 and n[1] == 0.0 and n[2] == 0.0:
        return n_smooth
    if dot(n, n_geometric) < 0.0:
        n = scale(n, -1.0)
    return kept_above(n_geometric, d, n)


@kernel
def coat_reflectance(coat, cos):
    """F: what the coat reflects of light arriving at cos to its normal (no weight); as
    Cycles 4.2 takes it (ClearCoat.at_normal), the Fresnel at its normal for any roughness."""
    if coat.roughness <= SHARP_ROUGHNESS or coat.at_normal:
        f, _ = fresnel_dielectric(cos, 1.0, coat.ior)
        return f
    return dielectric_fresnel_mean(coat.roughness, cos, coat.ior)


@kernel
def under_coat(coat, cos, f):
    """The RGB factor on everything below the coat (the module's `under`), F = f."""
    dim = max(0.0, 1.0 - coat.layer * f)
    sin2_t = (1.0 - cos * cos) / (coat.ior * coat.ior)
    path = 1.0 / math.sqrt(max(1.0 - sin2_t, 1e-12))
    tint = coat.tint
    return (
        dim * max(0.0, 1.0 + coat.layer * (tint[0] ** path - 1.0)),
        dim * max(0.0, 1.0 + coat.layer * (tint[1] ** path - 1.0)),
        dim * max(0.0, 1.0 + coat.layer * (tint[2] ** path - 1.0)),
    )


@kernel
def coat_glint(coat):
    """The rough coat's lobe for Blender's lights (core.kernels.microfacet.Gloss: single
    scattering GGX, as Cycles' coat is); none if the coat is sharp."""
    if coat.roughness <= SHARP_ROUGHNESS:
        return NO_GLINT
    alpha = coat.roughness * coat.roughness
    white = (1.0, 1.0, 1.0)
    return Gloss(alpha, False, ZERO3, ZERO3, ZERO3, ZERO3, coat.weight, coat.ior, 0.0, white, ZERO3)
