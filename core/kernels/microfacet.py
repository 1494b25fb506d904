"""Rough lobes lit by a light, as Cycles' microfacet BSDFs evaluate them: the glint of the
sun or a lamp on rough metal, plastic and car paint.

A rough lobe of roughness r (alpha = r^2) seen from unit v, lit from unit l about the unit
normal n, with the half vector h = (v + l) / |v + l|, reflects

    f cos(l) = F(v.h) D(h) G2(v, l) / (4 n.v)

D the distribution of microfacet normals (GGX's or Beckmann's), G2 = 1 / (1 + L(v) + L(l))
Smith's height-correlated masking and shadowing (Heitz 2014), F the lobe's Fresnel: Schlick's
F0 + (F90 - F0)(1 - v.h)^5 for metals and Glossy (F0 = F90: no Fresnel), the exact dielectric
reflectance of its IOR for a Principled BSDF's specular layer.

A single-scattering lobe loses the light that bounces between microfacets more than once:
rough white metal reflects only E(r, n.v) < 1 of what falls on it. Multiscatter GGX (every
closure's default since Blender 4.0) gives it back (Kulla and Conty 2017): the lobe times
1 + Fms (1 - E) / E, Fms = Fss E_avg / (1 - Fss (1 - E_avg)) the Fresnel of the light that
bounced, Fss the lobe's Fresnel averaged over the hemisphere, E_avg(r) the albedo averaged
over n.v. Fms depends on the roughness only, so the shader program adds it up per lobe
(Gloss.ms_*); E depends on n.v and is looked up here, in a table of our own
(core.kernels.ggx_albedo_table computes it; tests/core/kernels/test_microfacet.py checks it).
"""

import math
from typing import NamedTuple

import numpy as np

from ..jit.decorators import kernel
from .fresnel import fresnel_dielectric
from .ggx_albedo_values import (
    ALBEDO,
    ALBEDO_AVERAGE,
    DIELECTRIC_FRESNEL,
    DIELECTRIC_SIZE,
    TABLE_SIZE,
)
from .vec import add, dot, normalize, scale, sub

# Closure distributions (a closure step's operand; core.model.shader.DISTRIBUTIONS)
DIST_GGX, DIST_MULTI_GGX, DIST_BECKMANN = 0, 1, 2


class Gloss(NamedTuple):
    """A surface's rough lobes, added up for lights (core.kernels.shader_program's gloss)."""

    alpha: float  # the lobes' mean alpha; 0: no glint (sharp lobes see lights as mirrors)
    beckmann: bool  # Beckmann's distribution, else GGX's
    normal: tuple  # sum of weight x F0 of the Schlick lobes
    edge: tuple  # sum of weight x F90
    ms_normal: tuple  # sum of weight x Fms x F0 (multiscatter lobes only)
    ms_edge: tuple  # sum of weight x Fms x F90
    coat: float  # sum of the dielectric lobes' weights
    coat_ior: float  # their IOR
    coat_ms: float  # sum of their weight x Fms
    coat_tint: tuple  # their Specular Tint (RGB, white: none; `tinted_fresnel`)
    dip: tuple  # sum of weight x F82's dip (`f82_dip`) of the Schlick lobes


E_TABLE = np.array(ALBEDO.split(), float).reshape(TABLE_SIZE, TABLE_SIZE)
E_AVERAGE = np.array(ALBEDO_AVERAGE.split(), float)
F_MEAN = np.array(DIELECTRIC_FRESNEL.split(), float).reshape((DIELECTRIC_SIZE,) * 3)

# Gauss-Legendre nodes and weights on [0, 1], for a dielectric's mean Fresnel
_NODES, _WEIGHTS = np.polynomial.legendre.leggauss(16)
GAUSS_NODES = 0.5 * (_NODES + 1.0)
GAUSS_WEIGHTS = 0.5 * _WEIGHTS


@kernel
def ggx_albedo(roughness, mu):
    """E(r, mu), bilinear in the table."""
    last = TABLE_SIZE - 1
    x = min(max(roughness, 0.0), 1.0) * last
    y = min(max(mu, 0.0), 1.0) * last
    i, j = min(int(x), last - 1), min(int(y), last - 1)
    fx, fy = x - i, y - j
    low = E_TABLE[i, j] * (1.0 - fy) + E_TABLE[i, j + 1] * fy
    high = E_TABLE[i + 1, j] * (1.0 - fy) + E_TABLE[i + 1, j + 1] * fy
    return low * (1.0 - fx) + high * fx


@kernel
def ggx_albedo_average(roughness):
    """E_avg(r), linear in the table."""
    last = TABLE_SIZE - 1
    x = min(max(roughness, 0.0), 1.0) * last
    i = min(int(x), last - 1)
    f = x - i
    return E_AVERAGE[i] * (1.0 - f) + E_AVERAGE[i + 1] * f


@kernel
def dielectric_fresnel_mean(roughness, mu, ior):
    """F_mean(r, mu, z), trilinear in the table (z = sqrt((ior - 1) / (ior + 1)))."""
    last = DIELECTRIC_SIZE - 1
    x = min(max(roughness, 0.0), 1.0) * last
    y = min(max(mu, 0.0), 1.0) * last
    z = min(math.sqrt(max(ior - 1.0, 0.0) / (ior + 1.0)), 1.0) * last
    i, j, k = min(int(x), last - 1), min(int(y), last - 1), min(int(z), last - 1)
    fx, fy, fz = x - i, y - j, z - k
    total = 0.0
    for di in range(2):
        for dj in range(2):
            for dk in range(2):
                w = (fx if di else 1.0 - fx) * (fy if dj else 1.0 - fy) * (fz if dk else 1.0 - fz)
                total += w * F_MEAN[i + di, j + dj, k + dk]
    return total


@kernel
def rough_coat_albedo(gloss, roughness, cos_i):
    """What a rough dielectric layer of the gloss's IOR reflects in all of light arriving
    at cos_i, its whole lobe's (Cycles layers the diffuse below by it): F_mean E, and under
    Multiscatter GGX times 1 + Fms (1 - E) / E."""
    e = ggx_albedo(roughness, cos_i)
    albedo = dielectric_fresnel_mean(roughness, cos_i, gloss.coat_ior) * e
    if gloss.coat_ms > 0.0 and gloss.coat > 0.0:
        albedo *= 1.0 + gloss.coat_ms / gloss.coat * (1.0 - e) / max(e, 1e-6)
    return min(albedo, 1.0)


@kernel
def f82_dip(f0, tint):
    """Cycles' F82 tint (metals, from Blender 4.0): Schlick's curve from f0 to white, less
    b mu (1 - mu)^6, b chosen per channel so that at mu = 1/7 (82 degrees) the curve is
    Schlick's times the tint: b = Schlick(1/7) (1 - tint) 7 / (6/7)^6 (derived from that
    condition, as Cycles derives it). b: the dip (`schlick_dip` evaluates the curve)."""
    f = 6.0 / 7.0
    f5 = f**5
    return (
        (f0[0] + (1.0 - f0[0]) * f5) * 7.0 / (f5 * f) * (1.0 - tint[0]),
        (f0[1] + (1.0 - f0[1]) * f5) * 7.0 / (f5 * f) * (1.0 - tint[1]),
        (f0[2] + (1.0 - f0[2]) * f5) * 7.0 / (f5 * f) * (1.0 - tint[2]),
    )


@kernel
def schlick_dip(normal, edge, dip, mu):
    """Schlick's normal + (edge - normal)(1 - mu)^5, less F82's dip mu (1 - mu)^6, in 0..1
    (just Schlick's where there is no dip)."""
    s = (1.0 - mu) ** 5
    curve = add(normal, scale((edge[0] - normal[0], edge[1] - normal[1], edge[2] - normal[2]), s))
    if dip[0] == 0.0 and dip[1] == 0.0 and dip[2] == 0.0:
        return curve
    d = mu * s * (1.0 - mu)
    return (
        min(max(curve[0] - dip[0] * d, 0.0), 1.0),
        min(max(curve[1] - dip[1] * d, 0.0), 1.0),
        min(max(curve[2] - dip[2] * d, 0.0), 1.0),
    )


@kernel
def is_white(tint):
    return tint[0] == 1.0 and tint[1] == 1.0 and tint[2] == 1.0


@kernel
def tinted_fresnel(fresnel, ior, tint):
    """A specular layer's Fresnel under Cycles' Specular Tint (from Blender 4.0), per channel,
    as a factor on the untinted `fresnel` of the same IOR: Cycles keeps the real Fresnel's
    shape, s = (F - F0) / (1 - F0), and tints only its start, F0 t + (1 - F0 t) s."""
    f0 = ((ior - 1.0) / (ior + 1.0)) ** 2
    if fresnel <= 0.0 or f0 >= 1.0:
        return 1.0, 1.0, 1.0
    s = max(fresnel - f0, 0.0) / (1.0 - f0)
    return (
        (f0 * tint[0] + (1.0 - f0 * tint[0]) * s) / fresnel,
        (f0 * tint[1] + (1.0 - f0 * tint[1]) * s) / fresnel,
        (f0 * tint[2] + (1.0 - f0 * tint[2]) * s) / fresnel,
    )


@kernel
def multiscatter_fresnel(fss, e_average):
    """Fms: the Fresnel of light that bounced between microfacets, for a lobe whose mean
    Fresnel is fss (Kulla and Conty's, one fss cancelled: it multiplies the lobe's F)."""
    return fss * e_average / (1.0 - fss * (1.0 - e_average))


@kernel
def schlick_average(f0, f90):
    """The hemispherical mean 2 int (F0 + (F90 - F0)(1 - mu)^5) mu dmu = F0 + (F90 - F0) / 21."""
    return f0 + (f90 - f0) / 21.0


@kernel
def dielectric_average(ior):
    """The exact dielectric Fresnel's hemispherical mean 2 int F(mu) mu dmu, by 16-point
    Gauss-Legendre (F is smooth for ior > 1; below, total reflection makes it a kink)."""
    total = 0.0
    for k in range(GAUSS_NODES.shape[0]):
        mu = GAUSS_NODES[k]
        f, _ = fresnel_dielectric(mu, 1.0, ior)
        total += 2.0 * GAUSS_WEIGHTS[k] * f * mu
    return total


@kernel
def _lambda(alpha2, cos, beckmann):
    """Smith's Lambda of a direction at cos from the normal: GGX's closed form, Beckmann's
    exact one (with erf)."""
    tan2 = max(1.0 / max(cos * cos, 1e-300) - 1.0, 0.0)
    if not beckmann:
        return 0.5 * (math.sqrt(1.0 + alpha2 * tan2) - 1.0)
    if tan2 == 0.0:
        return 0.0
    a = 1.0 / math.sqrt(alpha2 * tan2)
    return 0.5 * (math.erf(a) - 1.0) + math.exp(-a * a) / (2.0 * a * math.sqrt(math.pi))


@kernel
def _distribution(alpha2, cos_h, beckmann):
    """D(h): the density of microfacet normals at cos_h from the normal."""
    c2 = cos_h * cos_h
    if beckmann:
        return math.exp((1.0 - 1.0 / c2) / alpha2) / (math.pi * alpha2 * c2 * c2)
    t = 1.0 + (alpha2 - 1.0) * c2
    return alpha2 / (math.pi * t * t)


@kernel
def _fresnel_sum(normal, edge, s):
    return add(normal, scale((edge[0] - normal[0], edge[1] - normal[1], edge[2] - normal[2]), s))


@kernel
def gloss_lit(gloss, n, to_viewer, light_dir):
    """pi f cos(l) (RGB) of the surface's rough lobes for light arriving along unit
    light_dir, seen along unit to_viewer about unit n: the module's formula, times pi as
    the emitters' terms are (their radiance holds the 1 / pi of a Lambertian kd)."""
    cos_v = dot(n, to_viewer)
    cos_l = dot(n, light_dir)
    if gloss.alpha <= 0.0 or cos_v <= 0.0 or cos_l <= 0.0:
        return 0.0, 0.0, 0.0
    h = normalize(add(to_viewer, light_dir))
    cos_h = dot(n, h)
    if cos_h <= 0.0:
        return 0.0, 0.0, 0.0
    alpha2 = gloss.alpha * gloss.alpha
    beckmann = gloss.beckmann
    g2 = 1.0 / (1.0 + _lambda(alpha2, cos_v, beckmann) + _lambda(alpha2, cos_l, beckmann))
    single = math.pi * _distribution(alpha2, cos_h, beckmann) * g2 / (4.0 * cos_v)
    v_h = min(max(dot(to_viewer, h), 0.0), 1.0)
    s = (1.0 - v_h) ** 5
    fresnel = _fresnel_sum(gloss.normal, gloss.edge, s)
    if gloss.dip[0] != 0.0 or gloss.dip[1] != 0.0 or gloss.dip[2] != 0.0:  # F82's
        fresnel = sub(fresnel, scale(gloss.dip, v_h * s * (1.0 - v_h)))
    coat_f = 0.0
    coat_colour = (1.0, 1.0, 1.0)
    if gloss.coat > 0.0:
        coat_f, _ = fresnel_dielectric(v_h, 1.0, gloss.coat_ior)
        if not is_white(gloss.coat_tint):
            coat_colour = tinted_fresnel(coat_f, gloss.coat_ior, gloss.coat_tint)
        fresnel = add(fresnel, scale(coat_colour, gloss.coat * coat_f))
    if max(gloss.ms_normal) > 0.0 or max(gloss.ms_edge) > 0.0 or gloss.coat_ms > 0.0:
        e = ggx_albedo(math.sqrt(gloss.alpha), cos_v)
        missing = (1.0 - e) / max(e, 1e-6)
        bounced = _fresnel_sum(gloss.ms_normal, gloss.ms_edge, s)
        bounced = add(bounced, scale(coat_colour, gloss.coat_ms * coat_f))
        fresnel = add(fresnel, scale(bounced, missing))
    return scale(fresnel, single)
