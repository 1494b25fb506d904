"""The exact dielectric Fresnel reflectance: glass, coats and the photons' bounces
(core.kernels.integrator, core.kernels.photons) and Blender's Fresnel and Layer Weight
nodes (core.kernels.facing_values) share it."""

import math

from ..jit.decorators import kernel


@kernel
def fresnel_dielectric(cos_i, n1, n2):
    """(reflectance F, cos of the refracted angle) for light going from index n1 into n2 at
    incidence cos_i in [0, 1]: the unpolarised average of the exact s and p reflectances.
    Total internal reflection gives (1, 0)."""
    eta = n1 / n2
    sin2_t = eta * eta * max(0.0, 1.0 - cos_i * cos_i)
    if sin2_t >= 1.0:
        return 1.0, 0.0
    cos_t = math.sqrt(1.0 - sin2_t)
    rs = (n1 * cos_i - n2 * cos_t) / (n1 * cos_i + n2 * cos_t)
    rp = (n1 * cos_t - n2 * cos_i) / (n1 * cos_t + n2 * cos_i)
    return 0.5 * (rs * rs + rp * rp), cos_t
