"""Rough diffuse reflection: the Diffuse BSDF's Roughness (and the Principled BSDF's Diffuse
Roughness, from Blender 4.3), as Cycles draws it, in one of two models.

- FON, Fujii's "qualitative" Oren-Nayar (Cycles before 4.3): f = rho/pi (A + B s/t), with
  A = 1 / (1 + c sigma), B = sigma A, c = 1/2 - 2/(3 pi); s = l.v - (n.l)(n.v), and
  t = max(n.l, n.v) where s > 0, else 1. At sigma 0 it is Lambert's rho/pi.
- EON, the energy-preserving Oren-Nayar of Portsmouth, Kutz and Hill (2024; Cycles from
  4.3): FON plus the light it loses between facets, a lobe
  rho_ms (1 - E(n.l)) (1 - E(n.v)) / (pi (1 - E_avg)). E(mu) = A + B G(mu)/pi is FON's
  directional albedo (G in closed form, below), E_avg = A + B (2/3 - 28/(15 pi)) its
  cosine-weighted mean, rho_ms = rho^2 E_avg / (1 - rho (1 - E_avg)). At rho = 1 the two
  lobes reflect all the light, from every direction (tests/core/test_rough_diffuse.py's
  furnace). Cycles weights that lobe by the closure's colour once more (rho^3 in all):
  measured against 4.5, to 1e-4; so does Whitted.

`rough_response` is the colour that stands in for kd in kd (n.l) L: pi f / (light).
"""

import math

from ..jit.decorators import kernel
from .vec import dot

# RenderSettings.rough_diffuse's models, in Options' numbering
ROUGH_EON, ROUGH_FON = 0, 1
_C = 0.5 - 2.0 / (3.0 * math.pi)
_G_MEAN = 2.0 / 3.0 - 28.0 / (15.0 * math.pi)  # 2 int_0^1 G(mu)/pi mu dmu


@kernel
def fon_terms(sigma):
    """(A, B) of FON at roughness sigma (clamped to 0..1, as Cycles clamps it)."""
    sigma = min(max(sigma, 0.0), 1.0)
    a = 1.0 / (1.0 + _C * sigma)
    return a, sigma * a


@kernel
def fon_g(mu):
    """G(mu) = int over the hemisphere of (s/t) cos(theta_l): FON's albedo is A + B G/pi.
    In closed form, theta = acos(mu): sin(theta) (theta - 2/3 - sin(theta) mu)
    + 2/3 tan(theta) (1 - sin^3(theta)), pi/2 - 2/3 at grazing."""
    mu = min(max(mu, 0.0), 1.0)
    if mu < 1e-6:
        return 0.5 * math.pi - 2.0 / 3.0
    theta = math.acos(mu)
    s = math.sqrt(max(0.0, 1.0 - mu * mu))
    return s * (theta - 2.0 / 3.0 - s * mu) + 2.0 / 3.0 * (s / mu) * (1.0 - s * s * s)


@kernel
def _multiple(kd_c, e_avg, lost_l, lost_v):
    """EON's multiple-scattering share for one channel of kd, Cycles' extra kd included."""
    rho = min(max(kd_c, 0.0), 1.0)
    rho_ms = rho * rho * e_avg / (1.0 - rho * (1.0 - e_avg))
    return kd_c * rho_ms * lost_l * lost_v / (1.0 - e_avg)


@kernel
def rough_response(kd, sigma, model, n, to_light, v):
    """kd's stand-in for light from unit direction to_light seen from v, about normal n."""
    a, b = fon_terms(sigma)
    mu_l, mu_v = max(dot(n, to_light), 0.0), max(dot(n, v), 0.0)
    s = dot(to_light, v) - mu_l * mu_v
    if s > 0.0:
        s /= max(mu_l, mu_v) + 1e-30
    single = a + b * s
    if model == ROUGH_FON:
        return (kd[0] * single, kd[1] * single, kd[2] * single)
    e_avg = a + b * _G_MEAN
    lost_l = 1.0 - (a + b * fon_g(mu_l) / math.pi)
    lost_v = 1.0 - (a + b * fon_g(mu_v) / math.pi)
    return (kd[0] * single + _multiple(kd[0], e_avg, lost_l, lost_v),
            kd[1] * single + _multiple(kd[1], e_avg, lost_l, lost_v),
            kd[2] * single + _multiple(kd[2], e_avg, lost_l, lost_v))  # fmt: skip


@kernel
def beyond_kd(kd, response, term):
    """`response` (rough_response's, or kd) over kd, channel by channel, times `term` (the
    shadow terminator's): the light's weight in the Diffuse Direct pass, 0 where kd is
    (Cycles divides by the colour safely)."""
    return (
        response[0] / kd[0] * term if kd[0] > 0.0 else 0.0,
        response[1] / kd[1] * term if kd[1] > 0.0 else 0.0,
        response[2] / kd[2] * term if kd[2] > 0.0 else 0.0,
    )


@kernel
def rough_albedo(kd, sigma, model, mu_v):
    """kd's stand-in for light falling evenly from every direction (the caustic photons,
    whose directions are not kept): the lobes' directional albedo seen at mu_v."""
    a, b = fon_terms(sigma)
    single = a + b * fon_g(mu_v) / math.pi
    if model == ROUGH_FON:
        return (kd[0] * single, kd[1] * single, kd[2] * single)
    e_avg = a + b * _G_MEAN
    lost_v = 1.0 - single
    # the lobe's mean over light directions of (1 - E(mu_l)) is 1 - E_avg
    return (kd[0] * single + _multiple(kd[0], e_avg, 1.0 - e_avg, lost_v),
            kd[1] * single + _multiple(kd[1], e_avg, 1.0 - e_avg, lost_v),
            kd[2] * single + _multiple(kd[2], e_avg, 1.0 - e_avg, lost_v))  # fmt: skip
