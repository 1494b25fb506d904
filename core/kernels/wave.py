"""Blender's Wave texture, as Cycles computes it: bands along an axis or the diagonal, or
rings around an axis or a point, each a sine, saw or triangle profile of 20 units' phase a
unit, its phase bent by fractal noise (core.kernels.noise) when Distortion is not 0."""

import math

from ..jit.decorators import kernel
from .noise import fbm

BANDS = 0  # the type (core.model.shader.WAVE_TYPES); rings: 1
DIAGONAL = 3  # the bands direction after X, Y, Z (WAVE_BANDS)
SPHERICAL = 3  # the rings direction after X, Y, Z (WAVE_RINGS)
SIN, SAW = 0, 1  # the profiles (WAVE_PROFILES); triangle: 2


@kernel
def wave_texture(p, distortion, detail, detail_scale, roughness, phase, kind, bands, rings,
                 profile):  # fmt: skip
    """The Wave texture's value at p (already scaled), 0..1."""
    # Cycles' nudge off whole coordinates, where its float32 bands would meet
    p = ((p[0] + 0.000001) * 0.999999, (p[1] + 0.000001) * 0.999999,
         (p[2] + 0.000001) * 0.999999)  # fmt: skip
    if kind == BANDS:
        n = (p[0] + p[1] + p[2]) * 10.0 if bands == DIAGONAL else p[bands] * 20.0
    else:
        x, y, z = p
        if rings != SPHERICAL:  # around an axis: that coordinate left out
            x, y, z = (
                (0.0 if rings == 0 else x),
                (0.0 if rings == 1 else y),
                (0.0 if rings == 2 else z),
            )
        n = math.sqrt(x * x + y * y + z * z) * 20.0
    n += phase
    if distortion != 0.0:
        q = (p[0] * detail_scale, p[1] * detail_scale, p[2] * detail_scale)
        detail = min(max(detail, 0.0), 15.0)
        n += distortion * (fbm(q, detail, max(roughness, 0.0), 2.0, True) * 2.0 - 1.0)
    if profile == SIN:
        return 0.5 + 0.5 * math.sin(n - 0.5 * math.pi)
    n /= 2.0 * math.pi
    if profile == SAW:
        return n - math.floor(n)
    return abs(n - math.floor(n + 0.5)) * 2.0
