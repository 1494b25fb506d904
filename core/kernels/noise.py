"""Blender's Noise texture (3D, fractal Brownian motion), as Cycles computes it: Perlin
noise whose lattice gradients come from Bob Jenkins' lookup3 hash of the cell's integer
corner, faded by 6t^5 - 15t^4 + 10t^3 and scaled by 0.982; octaves summed with Detail,
Roughness and Lacunarity; Distortion and the Color output by the same noise at fixed
offsets. The hash runs in 32-bit unsigned arithmetic held in int64 (every step reduced
mod 2^32), so each cell's gradient is Cycles' own; the rest is float64 where Cycles uses
float32, a difference of rounding only (the texture is continuous)."""

import math

import numpy as np

from ..jit.decorators import kernel

_LOW32 = 0xFFFFFFFF
# Cycles scales 3D Perlin noise so that its range is about [-1, 1]
NOISE_SCALE_3D = 0.9820
# Cycles repeats noise every 100000 units along each axis (float precision)
_REPEAT = 100000.0


@kernel
def _rot(x, k):
    return ((x << k) | (x >> (32 - k))) & _LOW32


@kernel
def _final(a, b, c):
    """lookup3's final mixing of three 32-bit values; returns c."""
    c = ((c ^ b) - _rot(b, 14)) & _LOW32
    a = ((a ^ c) - _rot(c, 11)) & _LOW32
    b = ((b ^ a) - _rot(a, 25)) & _LOW32
    c = ((c ^ b) - _rot(b, 16)) & _LOW32
    a = ((a ^ c) - _rot(c, 4)) & _LOW32
    b = ((b ^ a) - _rot(a, 14)) & _LOW32
    c = ((c ^ b) - _rot(b, 24)) & _LOW32
    return c


@kernel
def hash_uint3(kx, ky, kz):
    """Cycles' hash_uint3 of three integers taken as 32-bit unsigned."""
    start = (0xDEADBEEF + (3 << 2) + 13) & _LOW32
    a = (start + (kx & _LOW32)) & _LOW32
    b = (start + (ky & _LOW32)) & _LOW32
    c = (start + (kz & _LOW32)) & _LOW32
    return _final(a, b, c)


@kernel
def _mix(a, b, c):
    """lookup3's mixing of three 32-bit values."""
    a = ((a - c) & _LOW32) ^ _rot(c, 4)
    c = (c + b) & _LOW32
    b = ((b - a) & _LOW32) ^ _rot(a, 6)
    a = (a + c) & _LOW32
    c = ((c - b) & _LOW32) ^ _rot(b, 8)
    b = (b + a) & _LOW32
    a = ((a - c) & _LOW32) ^ _rot(c, 16)
    c = (c + b) & _LOW32
    b = ((b - a) & _LOW32) ^ _rot(a, 19)
    a = (a + c) & _LOW32
    c = ((c - b) & _LOW32) ^ _rot(b, 4)
    b = (b + a) & _LOW32
    return a, b, c


@kernel
def hash_uint4(kx, ky, kz, kw):
    """Cycles' hash_uint4 of four integers taken as 32-bit unsigned."""
    start = (0xDEADBEEF + (4 << 2) + 13) & _LOW32
    a = (start + (kx & _LOW32)) & _LOW32
    b = (start + (ky & _LOW32)) & _LOW32
    c = (start + (kz & _LOW32)) & _LOW32
    a, b, c = _mix(a, b, c)
    a = (a + (kw & _LOW32)) & _LOW32
    return _final(a, b, c)


@kernel
def hash_uint2(kx, ky):
    """Cycles' hash_uint2 of two integers taken as 32-bit unsigned."""
    start = (0xDEADBEEF + (2 << 2) + 13) & _LOW32
    a = (start + (kx & _LOW32)) & _LOW32
    b = (start + (ky & _LOW32)) & _LOW32
    return _final(a, b, start)


def random_offset(seed: float) -> tuple:
    """Cycles' random_float3_offset(seed): 100 + 100 hash((seed, i)) per axis, in float32,
    the hash of the floats' bits mapped to [0, 1] by n / 0xFFFFFFFF."""

    def bits(x: float) -> int:
        return int(np.array(x, np.float32).view(np.uint32))

    out = []
    for axis in range(3):
        n = hash_uint2(bits(seed), bits(float(axis)))
        unit = np.float32(n) * (np.float32(1.0) / np.float32(0xFFFFFFFF))
        out.append(float(np.float32(100.0) + unit * np.float32(100.0)))
    return tuple(out)


# random_offset(seed) for the seeds Cycles uses: Distortion's (0, 1, 2) and the Color's
# green and blue (3 and 4). Written out, not computed at import (that would compile the
# hash in every process); tests/core/test_noise_texture.py recomputes them
OFFSETS = (
    (186.03128051757812, 114.9559555053711, 154.447509765625),
    (199.83999633789062, 162.2926025390625, 154.04823303222656),
    (111.63384246826172, 157.369384765625, 199.08810424804688),
    (165.44528198242188, 162.76821899414062, 193.40841674804688),
    (155.58091735839844, 177.15463256835938, 138.14002990722656),
)


@kernel
def _fade(t):
    return t * t * t * (t * (t * 6.0 - 15.0) + 10.0)


@kernel
def _grad3(hashed, x, y, z):
    h = hashed & 15
    u = x if h < 8 else y
    vt = x if (h == 12 or h == 14) else z
    v = y if h < 4 else vt
    return (-u if h & 1 else u) + (-v if h & 2 else v)


@kernel
def perlin_3d(x, y, z):
    """Cycles' perlin_3d: gradients at the cell's eight corners, blended by the fades."""
    fx, fy, fz = math.floor(x), math.floor(y), math.floor(z)
    ix, iy, iz = int(fx), int(fy), int(fz)
    fx, fy, fz = x - fx, y - fy, z - fz
    u, v, w = _fade(fx), _fade(fy), _fade(fz)
    v0 = _grad3(hash_uint3(ix, iy, iz), fx, fy, fz)
    v1 = _grad3(hash_uint3(ix + 1, iy, iz), fx - 1.0, fy, fz)
    v2 = _grad3(hash_uint3(ix, iy + 1, iz), fx, fy - 1.0, fz)
    v3 = _grad3(hash_uint3(ix + 1, iy + 1, iz), fx - 1.0, fy - 1.0, fz)
    v4 = _grad3(hash_uint3(ix, iy, iz + 1), fx, fy, fz - 1.0)
    v5 = _grad3(hash_uint3(ix + 1, iy, iz + 1), fx - 1.0, fy, fz - 1.0)
    v6 = _grad3(hash_uint3(ix, iy + 1, iz + 1), fx, fy - 1.0, fz - 1.0)
    v7 = _grad3(hash_uint3(ix + 1, iy + 1, iz + 1), fx - 1.0, fy - 1.0, fz - 1.0)
    u1, w1, v_1 = 1.0 - u, 1.0 - w, 1.0 - v
    return w1 * (v_1 * (v0 * u1 + v1 * u) + v * (v2 * u1 + v3 * u)) + w * (
        v_1 * (v4 * u1 + v5 * u) + v * (v6 * u1 + v7 * u)
    )


@kernel
def _wrapped(x):
    """Cycles' fmod(x, 100000) plus its half-unit correction beyond 10^6."""
    correction = 0.5 if abs(x) >= 1000000.0 else 0.0
    return x - _REPEAT * np.trunc(x / _REPEAT) + correction


@kernel
def signed_noise(p):
    """Cycles' snoise_3d: Perlin noise in about [-1, 1]."""
    return NOISE_SCALE_3D * perlin_3d(_wrapped(p[0]), _wrapped(p[1]), _wrapped(p[2]))


@kernel
def fbm(p, detail, roughness, lacunarity, normalize):
    """Cycles' noise_fbm (3D): octaves 0..floor(detail) and the fraction of the next."""
    fscale, amp, maxamp, total = 1.0, 1.0, 0.0, 0.0
    for _ in range(int(detail) + 1):
        t = signed_noise((fscale * p[0], fscale * p[1], fscale * p[2]))
        total += t * amp
        maxamp += amp
        amp *= roughness
        fscale *= lacunarity
    rmd = detail - math.floor(detail)
    if rmd != 0.0:
        t = signed_noise((fscale * p[0], fscale * p[1], fscale * p[2]))
        total2 = total + t * amp
        if normalize:
            a, b = 0.5 * total / maxamp + 0.5, 0.5 * total2 / (maxamp + amp) + 0.5
        else:
            a, b = total, total2
        return a * (1.0 - rmd) + b * rmd
    return 0.5 * total / maxamp + 0.5 if normalize else total


@kernel
def _shifted(p, offset):
    return (p[0] + offset[0], p[1] + offset[1], p[2] + offset[2])


@kernel
def noise_texture(p, detail, roughness, lacunarity, distortion, normalize, with_colour):
    """Blender's Noise texture at p (already scaled): (Fac, Color); without `with_colour`
    the Color is the Fac repeated (nothing reads it)."""
    detail = min(max(detail, 0.0), 15.0)
    roughness = max(roughness, 0.0)
    if distortion != 0.0:
        p = (
            p[0] + signed_noise(_shifted(p, OFFSETS[0])) * distortion,
            p[1] + signed_noise(_shifted(p, OFFSETS[1])) * distortion,
            p[2] + signed_noise(_shifted(p, OFFSETS[2])) * distortion,
        )
    value = fbm(p, detail, roughness, lacunarity, normalize)
    if not with_colour:
        return value, (value, value, value)
    green = fbm(_shifted(p, OFFSETS[3]), detail, roughness, lacunarity, normalize)
    blue = fbm(_shifted(p, OFFSETS[4]), detail, roughness, lacunarity, normalize)
    return value, (value, green, blue)
