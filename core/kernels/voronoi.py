"""Blender's Voronoi texture (3D; features F1, F2 and Smooth F1; the four distance metrics;
fractal octaves), as Cycles computes it: one feature point per unit cell, placed at the
cell's corner plus randomness times a hash of the cell, the nearest (F1) or second nearest
(F2) of the 27 cells around the point found; Distance, Color (a hash of that cell) and
Position. Smooth F1 blends the 125 cells of the 5 x 5 x 5 block around the point's in a
fixed order, each pulled in by a smoothstep of how much nearer it is than the blend so far
(Inigo Quilez's smooth minimum), which rounds F1's creases into valleys as wide as
Smoothness.

The cell hash changed with Blender 5.0, so a graph says which it was made in:
HASH_LOOKUP3 (before 5.0) hashes the bits of the cell's corner as float32 numbers with
lookup3, one hash_uint3 and two hash_uint4 mapped to [0, 1] by n / 2^32; HASH_PCG (5.0 on)
hashes the integer corner with the PCG 3D hash in wrapping 32-bit arithmetic, mapped by
n / 2^31. Both are computed bit for bit (int64 masked to 32 bits); the distances are
float64 where Cycles' are float32, a difference of rounding only.
"""

import math

import numpy as np

from ..jit.decorators import kernel
from .noise import hash_uint3, hash_uint4

# The numbers of core.model.shader's VORONOI_HASHES, VORONOI_FEATURES and VORONOI_METRICS
HASH_LOOKUP3, HASH_PCG = 0, 1
_F2, _SMOOTH_F1 = 1, 2
_MANHATTAN, _CHEBYCHEV, _MINKOWSKI = 1, 2, 3

_LOW32 = 0xFFFFFFFF
_ONE_BITS, _TWO_BITS = 0x3F800000, 0x40000000  # 1.0f and 2.0f
_TO_UNIT_LOOKUP3 = 2.0**-32  # 1 / (float)0xFFFFFFFF: the divisor rounds to 2^32
_TO_UNIT_PCG = 2.0**-31  # 1 / (float)0x7FFFFFFF: 2^31


@kernel
def float_bits_of_whole(n):
    """The float32 bit pattern of the whole number n (|n| < 2^31): a cell's corner."""
    if n == 0:
        return 0
    sign = 0
    if n < 0:
        sign, n = 1 << 31, -n
    exponent = 0
    while (n >> (exponent + 1)) > 0:
        exponent += 1
    # beyond float32's whole numbers (2^24) Cycles' corner was rounded already: truncated
    shifted = n << (23 - exponent) if exponent <= 23 else n >> (exponent - 23)
    mantissa = shifted & 0x7FFFFF
    return sign | ((exponent + 127) << 23) | mantissa


@kernel
def _unit(h, to_unit):
    """A hash mapped to [0, 1] as Cycles does: the integer rounded to float32, scaled."""
    return float(np.float32(h)) * to_unit


@kernel
def _wrap32(x):
    """x reduced to a signed 32-bit integer, as C's wrapping int arithmetic leaves it."""
    return ((x + (1 << 31)) & _LOW32) - (1 << 31)


@kernel
def hash_pcg3d(x, y, z):
    """Cycles' hash_pcg3d_i of three signed 32-bit integers (arithmetic shift, as C's
    >> of a negative int on every compiler Cycles supports)."""
    x = _wrap32(x * 1664525 + 1013904223)
    y = _wrap32(y * 1664525 + 1013904223)
    z = _wrap32(z * 1664525 + 1013904223)
    x = _wrap32(x + y * z)
    y = _wrap32(y + z * x)
    z = _wrap32(z + x * y)
    x, y, z = x ^ (x >> 16), y ^ (y >> 16), z ^ (z >> 16)
    x = _wrap32(x + y * z)
    y = _wrap32(y + z * x)
    z = _wrap32(z + x * y)
    return x & 0x7FFFFFFF, y & 0x7FFFFFFF, z & 0x7FFFFFFF


@kernel
def cell_hash(flavour, cx, cy, cz):
    """Three numbers in [0, 1] for the cell whose corner is the whole numbers (cx, cy, cz):
    Cycles' hash_float3_to_float3 (HASH_LOOKUP3) or hash_int3_to_float3 (HASH_PCG)."""
    if flavour == HASH_PCG:
        hx, hy, hz = hash_pcg3d(cx, cy, cz)
        return _unit(hx, _TO_UNIT_PCG), _unit(hy, _TO_UNIT_PCG), _unit(hz, _TO_UNIT_PCG)
    bx, by, bz = float_bits_of_whole(cx), float_bits_of_whole(cy), float_bits_of_whole(cz)
    return (
        _unit(hash_uint3(bx, by, bz), _TO_UNIT_LOOKUP3),
        _unit(hash_uint4(bx, by, bz, _ONE_BITS), _TO_UNIT_LOOKUP3),
        _unit(hash_uint4(bx, by, bz, _TWO_BITS), _TO_UNIT_LOOKUP3),
    )


@kernel
def voronoi_distance(metric, exponent, dx, dy, dz):
    """The distance of the offset (dx, dy, dz) by `metric` (Minkowski's `exponent`)."""
    ax, ay, az = abs(dx), abs(dy), abs(dz)
    if metric == _MANHATTAN:
        return ax + ay + az
    if metric == _CHEBYCHEV:
        return max(ax, ay, az)
    if metric == _MINKOWSKI:
        return (ax**exponent + ay**exponent + az**exponent) ** (1.0 / exponent)
    return math.sqrt(dx * dx + dy * dy + dz * dz)


@kernel
def voronoi_octave(p, feature, metric, exponent, randomness, flavour):
    """One octave at p (scaled): (distance, colour, position) of the nearest feature point
    (F1) or the second nearest (F2) among the 27 cells around p's."""
    fx, fy, fz = math.floor(p[0]), math.floor(p[1]), math.floor(p[2])
    cx, cy, cz = int(fx), int(fy), int(fz)
    lx, ly, lz = p[0] - fx, p[1] - fy, p[2] - fz
    best = second = math.inf
    best_cell = second_cell = (0, 0, 0)
    best_point = second_point = (0.0, 0.0, 0.0)
    for k in range(-1, 2):
        for j in range(-1, 2):
            for i in range(-1, 2):
                hx, hy, hz = cell_hash(flavour, cx + i, cy + j, cz + k)
                point = (i + hx * randomness, j + hy * randomness, k + hz * randomness)
                d = voronoi_distance(metric, exponent, point[0] - lx, point[1] - ly, point[2] - lz)
                if d < best:
                    second, second_cell, second_point = best, best_cell, best_point
                    best, best_cell, best_point = d, (i, j, k), point
                elif d < second:
                    second, second_cell, second_point = d, (i, j, k), point
    if feature == _F2:
        best, best_cell, best_point = second, second_cell, second_point
    colour = cell_hash(flavour, cx + best_cell[0], cy + best_cell[1], cz + best_cell[2])
    position = (best_point[0] + fx, best_point[1] + fy, best_point[2] + fz)
    return best, colour, position


@kernel
def _lerp(a, b, t):
    return (1.0 - t) * a + t * b


@kernel
def _lerp3(a, b, t):
    return (_lerp(a[0], b[0], t), _lerp(a[1], b[1], t), _lerp(a[2], b[2], t))


@kernel
def _smoothstep01(x):
    t = min(max(x, 0.0), 1.0)
    return t * t * (3.0 - 2.0 * t)


@kernel
def voronoi_smooth_octave(p, metric, exponent, randomness, smoothness, flavour):
    """One Smooth F1 octave at p (scaled), smoothness > 0 (Cycles' half of the node's
    Smoothness, at most 0.5): (distance, colour, position). The first cell is taken whole;
    each next one moves the blend towards itself by a smoothstep weight h, and the blend
    is lowered by smoothness h (1 - h), the smooth minimum's rounding, which colour and
    position share divided by 1 + 3 smoothness."""
    fx, fy, fz = math.floor(p[0]), math.floor(p[1]), math.floor(p[2])
    cx, cy, cz = int(fx), int(fy), int(fz)
    lx, ly, lz = p[0] - fx, p[1] - fy, p[2] - fz
    distance = 0.0
    colour = (0.0, 0.0, 0.0)
    position = (0.0, 0.0, 0.0)
    first = True
    for k in range(-2, 3):
        for j in range(-2, 3):
            for i in range(-2, 3):
                hx, hy, hz = cell_hash(flavour, cx + i, cy + j, cz + k)
                point = (i + hx * randomness, j + hy * randomness, k + hz * randomness)
                d = voronoi_distance(metric, exponent, point[0] - lx, point[1] - ly, point[2] - lz)
                if first:
                    h = 1.0
                    first = False
                else:
                    h = _smoothstep01(0.5 + 0.5 * (distance - d) / smoothness)
                correction = smoothness * h * (1.0 - h)
                distance = _lerp(distance, d, h) - correction
                correction /= 1.0 + 3.0 * smoothness
                colour = (_lerp(colour[0], hx, h) - correction,
                          _lerp(colour[1], hy, h) - correction,
                          _lerp(colour[2], hz, h) - correction)  # fmt: skip
                position = (_lerp(position[0], point[0], h) - correction,
                            _lerp(position[1], point[1], h) - correction,
                            _lerp(position[2], point[2], h) - correction)  # fmt: skip
    return distance, colour, (position[0] + fx, position[1] + fy, position[2] + fz)


@kernel
def voronoi_texture(p, scale, detail, roughness, lacunarity, randomness, exponent, feature,
                    metric, normalize, flavour, smoothness):  # fmt: skip
    """Blender's Voronoi texture at coordinate p (unscaled): (Distance, Color, Position),
    Cycles' fractal_voronoi_x_fx: octaves 0..ceil(detail), the last by detail's fraction,
    each at lacunarity times the last's frequency and roughness times its amplitude.
    Smooth F1 at Smoothness 0 is F1."""
    detail = min(max(detail, 0.0), 15.0)
    roughness = min(max(roughness, 0.0), 1.0)
    randomness = min(max(randomness, 0.0), 1.0)
    smoothness = min(max(smoothness / 2.0, 0.0), 0.5)
    if feature == _SMOOTH_F1 and smoothness == 0.0:
        feature = 0
    q = (p[0] * scale, p[1] * scale, p[2] * scale)
    reach = 0.5 + 0.5 * randomness
    max_distance = voronoi_distance(metric, exponent, reach, reach, reach)
    if feature == _F2:
        max_distance *= 2.0
    amplitude, max_amplitude, frequency = 1.0, 0.0, 1.0
    distance, colour, position = 0.0, (0.0, 0.0, 0.0), (0.0, 0.0, 0.0)
    single = detail == 0.0 or roughness == 0.0
    for i in range(int(math.ceil(detail)) + 1):
        scaled = (q[0] * frequency, q[1] * frequency, q[2] * frequency)
        if feature == _SMOOTH_F1:
            d, c, at = voronoi_smooth_octave(scaled, metric, exponent, randomness, smoothness,
                                             flavour)  # fmt: skip
        else:
            d, c, at = voronoi_octave(scaled, feature, metric, exponent, randomness, flavour)
        if single:
            max_amplitude, distance, colour, position = 1.0, d, c, at
            break
        at = (at[0] / frequency, at[1] / frequency, at[2] / frequency)
        if i <= detail:
            max_amplitude += amplitude
            distance += d * amplitude
            colour = (colour[0] + c[0] * amplitude, colour[1] + c[1] * amplitude,
                      colour[2] + c[2] * amplitude)  # fmt: skip
            position = _lerp3(position, at, amplitude)
            frequency *= lacunarity
            amplitude *= roughness
        else:
            rest = detail - math.floor(detail)
            if rest != 0.0:
                max_amplitude = _lerp(max_amplitude, max_amplitude + amplitude, rest)
                distance = _lerp(distance, distance + d * amplitude, rest)
                colour = _lerp3(colour, (colour[0] + c[0] * amplitude, colour[1] + c[1] * amplitude,
                                         colour[2] + c[2] * amplitude), rest)  # fmt: skip
                position = _lerp3(position, _lerp3(position, at, amplitude), rest)
    if normalize:
        distance /= max_amplitude * max_distance
        colour = (colour[0] / max_amplitude, colour[1] / max_amplitude, colour[2] / max_amplitude)
    if scale != 0.0:
        position = (position[0] / scale, position[1] / scale, position[2] / scale)
    else:
        position = (0.0, 0.0, 0.0)
    return distance, colour, position
