"""Blender's White Noise texture, as Cycles computes it: a lookup3 hash of the float32 bit
patterns of its input (core.kernels.noise's hashes), in 1 to 4 dimensions, mapped to 0..1.

Its value jumps with every bit of the input, so it equals Cycles' where the input is the
same float32 number in both: whole-number cells (a Floor or Snap of the coordinates, the
use it is made for), not raw coordinates, which Whitted computes in float64."""

import math

import numpy as np

from ..jit.decorators import kernel
from .noise import _final, hash_uint2, hash_uint3, hash_uint4

_LOW32 = 0xFFFFFFFF
_TO_UNIT = 2.0**-32  # Cycles' 1 / (float)0xFFFFFFFF: the divisor rounds to 2^32
_ONE, _TWO = 0x3F800000, 0x40000000  # the bits of 1.0f and 2.0f


@kernel
def float32_bits(x):
    """The bit pattern of x rounded to float32 (Cycles' __float_as_uint)."""
    y = float(np.float32(x))
    sign = (1 << 31) if math.copysign(1.0, y) < 0.0 else 0
    y = abs(y)
    if y == 0.0:
        return sign
    if math.isinf(y):
        return sign | 0x7F800000
    mantissa, exponent = math.frexp(y)  # y = mantissa 2^exponent, mantissa in [0.5, 1)
    biased = exponent - 1 + 127
    if biased <= 0:  # subnormal: no hidden bit
        return sign | int(y * 2.0**149)
    return sign | (biased << 23) | (int(mantissa * 2.0**24) & 0x7FFFFF)


@kernel
def _hash1(kx):
    """Cycles' hash_uint of one integer."""
    start = (0xDEADBEEF + (1 << 2) + 13) & _LOW32
    return _final((start + (kx & _LOW32)) & _LOW32, start, start)


@kernel
def _unit(h):
    return float(np.float32(h)) * _TO_UNIT


@kernel
def white_noise(dimensions, p, w):
    """(value, colour) of the texture at vector p and number w in `dimensions` (1 uses w,
    2 p's x and y, 3 p, 4 p and w)."""
    x, y, z, t = float32_bits(p[0]), float32_bits(p[1]), float32_bits(p[2]), float32_bits(w)
    if dimensions == 1:
        return _unit(_hash1(t)), (_unit(_hash1(t)), _unit(hash_uint2(t, _ONE)),
                                  _unit(hash_uint2(t, _TWO)))  # fmt: skip
    if dimensions == 2:
        return _unit(hash_uint2(x, y)), (_unit(hash_uint2(x, y)), _unit(hash_uint3(x, y, _ONE)),
                                         _unit(hash_uint3(x, y, _TWO)))  # fmt: skip
    if dimensions == 3:
        return _unit(hash_uint3(x, y, z)), (
            _unit(hash_uint3(x, y, z)), _unit(hash_uint4(x, y, z, _ONE)),
            _unit(hash_uint4(x, y, z, _TWO)),
        )  # fmt: skip
    value = _unit(hash_uint4(x, y, z, t))
    return value, (value, _unit(hash_uint4(z, x, t, y)), _unit(hash_uint4(t, z, y, x)))
