"""The Voronoi texture's kernels (core.kernels.voronoi) against references written here in
numpy: the float32 bit patterns of cell corners, both cell hashes (lookup3 on uint32,
PCG on wrapping int32), and the texture itself by brute force over a 5 x 5 x 5 block of
cells with every metric; with randomness 0, against the closed form of the lattice. That
the values are Blender's own is tests/blender/test_cycles_textures.py's check."""

import math

import numpy as np
import pytest

from core.kernels.noise import hash_uint4
from core.kernels.voronoi import (
    HASH_LOOKUP3,
    HASH_PCG,
    cell_hash,
    float_bits_of_whole,
    hash_pcg3d,
    voronoi_texture,
)

METRICS = ("EUCLIDEAN", "MANHATTAN", "CHEBYCHEV", "MINKOWSKI")


def _rot(x, k):
    return ((x << np.uint32(k)) | (x >> np.uint32(32 - k))).astype(np.uint32)


def _lookup3_4(kx, ky, kz, kw):
    """Bob Jenkins' lookup3 (hashword of four words, initval 13), in numpy uint32."""
    with np.errstate(over="ignore"):
        a = b = c = np.uint32(0xDEADBEEF + (4 << 2) + 13)
        a, b, c = a + np.uint32(kx), b + np.uint32(ky), c + np.uint32(kz)
        a -= c
        a ^= _rot(c, 4)
        c += b  # noqa: E702
        b -= a
        b ^= _rot(a, 6)
        a += c  # noqa: E702
        c -= b
        c ^= _rot(b, 8)
        b += a  # noqa: E702
        a -= c
        a ^= _rot(c, 16)
        c += b  # noqa: E702
        b -= a
        b ^= _rot(a, 19)
        a += c  # noqa: E702
        c -= b
        c ^= _rot(b, 4)
        b += a  # noqa: E702
        a += np.uint32(kw)
        c ^= b
        c -= _rot(b, 14)  # noqa: E702
        a ^= c
        a -= _rot(c, 11)  # noqa: E702
        b ^= a
        b -= _rot(a, 25)  # noqa: E702
        c ^= b
        c -= _rot(b, 16)  # noqa: E702
        a ^= c
        a -= _rot(c, 4)  # noqa: E702
        b ^= a
        b -= _rot(a, 14)  # noqa: E702
        c ^= b
        c -= _rot(b, 24)  # noqa: E702
    return int(c)


def _pcg3d(v):
    """hash_pcg3d_i in numpy int32 (wrapping; >> arithmetic)."""
    with np.errstate(over="ignore"):
        x, y, z = (np.int32(n) * np.int32(1664525) + np.int32(1013904223) for n in v)
        x += y * z
        y += z * x
        z += x * y  # noqa: E702
        x ^= x >> np.int32(16)
        y ^= y >> np.int32(16)
        z ^= z >> np.int32(16)  # noqa: E702
        x += y * z
        y += z * x
        z += x * y  # noqa: E702
    return tuple(int(n & np.int32(0x7FFFFFFF)) for n in (x, y, z))


def test_a_cell_corners_float32_bits_are_numpys():
    for n in [0, 1, -1, 2, 3, -7, 100, 12345, -99999, 2**23 + 1, 2**24, -(2**24)]:
        expected = int(np.array(float(n), np.float32).view(np.uint32))
        assert float_bits_of_whole(n) == expected, n


def test_hash_uint4_is_lookup3():
    rng = np.random.default_rng(3)
    for k in rng.integers(0, 2**32, size=(50, 4)):
        assert hash_uint4(*(int(x) for x in k)) == _lookup3_4(*k)


def test_the_pcg_hash_wraps_as_32_bit_int():
    rng = np.random.default_rng(4)
    for k in list(rng.integers(-(2**20), 2**20, size=(50, 3))) + [(0, 0, 0), (-1, -1, -1)]:
        assert hash_pcg3d(*(int(x) for x in k)) == _pcg3d(k)


def _reference_hash(flavour, cell):
    """A cell's three numbers by the references above: Cycles' float3 and int3 hashes."""
    if flavour == HASH_PCG:
        return np.array(_pcg3d(cell), np.float32).astype(float) * 2.0**-31
    bits = [int(np.array(float(c), np.float32).view(np.uint32)) for c in cell]
    words = (
        _lookup3_3(*bits),
        _lookup3_4(*bits, 0x3F800000),
        _lookup3_4(*bits, 0x40000000),
    )
    return np.array(words, np.float32).astype(float) * 2.0**-32


def _lookup3_3(kx, ky, kz):
    """lookup3 of three words (the hash_uint3 the Noise texture uses, tested there)."""
    from core.kernels.noise import hash_uint3

    return hash_uint3(kx, ky, kz)


@pytest.mark.parametrize("flavour", [HASH_LOOKUP3, HASH_PCG])
def test_cell_hashes_are_cycles_float3_and_int3_hashes(flavour):
    for cell in [(0, 0, 0), (3, -2, 7), (-40, 11, 0), (1000, -1000, 5)]:
        np.testing.assert_array_equal(cell_hash(flavour, *cell), _reference_hash(flavour, cell))


def _distance(metric, offset, exponent):
    a = np.abs(offset)
    if metric == "MANHATTAN":
        return a.sum(axis=-1)
    if metric == "CHEBYCHEV":
        return a.max(axis=-1)
    if metric == "MINKOWSKI":
        return (a**exponent).sum(axis=-1) ** (1.0 / exponent)
    return np.sqrt((offset**2).sum(axis=-1))


def _brute_force(q, flavour, randomness, metric, exponent, second):
    """F1 or F2 at the scaled point q over the 5 x 5 x 5 cells around it."""
    base = np.floor(q).astype(int)
    cells = [tuple(base + (i, j, k)) for i in range(-2, 3) for j in range(-2, 3)
             for k in range(-2, 3)]  # fmt: skip
    points = np.array([np.array(c) + _reference_hash(flavour, c) * randomness for c in cells])
    d = _distance(metric, points - q, exponent)
    order = np.argsort(d, kind="stable")
    pick = order[1 if second else 0]
    return d[pick], _reference_hash(flavour, cells[pick]), points[pick]


@pytest.mark.parametrize("metric", METRICS)
@pytest.mark.parametrize("flavour", [HASH_LOOKUP3, HASH_PCG])
def test_the_texture_is_the_nearest_and_second_nearest_feature_point(metric, flavour):
    rng = np.random.default_rng(11)
    scale, exponent = 2.5, 1.7
    for p in rng.uniform(-4.0, 4.0, size=(30, 3)):
        for feature in (0, 1):
            got = voronoi_texture(tuple(p), scale, 0.0, 0.5, 2.0, 0.8, exponent, feature,
                                  METRICS.index(metric), False, flavour, 1.0)  # fmt: skip
            d, colour, point = _brute_force(p * scale, flavour, 0.8, metric, exponent, feature)
            assert math.isclose(got[0], d, rel_tol=1e-12, abs_tol=1e-12)
            np.testing.assert_allclose(got[1], colour, rtol=1e-12)
            np.testing.assert_allclose(got[2], point / scale, rtol=1e-12)


def test_with_no_randomness_the_points_are_the_lattice_and_octaves_add_as_fbm():
    """Randomness 0: F1 is the distance to the nearest whole-number point; Detail 1 adds
    the octave at twice the frequency at Roughness times the amplitude, and Normalize
    divides by the amplitudes' sum and the largest F1 (half the cell's diagonal)."""
    rng = np.random.default_rng(12)
    for p in rng.uniform(-3.0, 3.0, size=(20, 3)):
        q = p * 3.0
        f1 = float(np.linalg.norm(q - np.round(q)))
        f1_twice = float(np.linalg.norm(2 * q - np.round(2 * q)))
        single = voronoi_texture(tuple(p), 3.0, 0.0, 0.5, 2.0, 0.0, 1.0, 0, 0, False, HASH_PCG, 1.0)
        assert math.isclose(single[0], f1, rel_tol=1e-12)
        np.testing.assert_allclose(single[2], np.round(q) / 3.0, rtol=1e-12, atol=1e-15)
        fractal = voronoi_texture(tuple(p), 3.0, 1.0, 0.6, 2.0, 0.0, 1.0, 0, 0, True, HASH_PCG, 1.0)
        expected = (f1 + 0.6 * f1_twice) / (1.6 * math.sqrt(3.0) * 0.5)
        assert math.isclose(fractal[0], expected, rel_tol=1e-12)


def _smooth_reference(q, flavour, randomness, metric, exponent, smoothness):
    """Smooth F1 at the scaled point q: the polynomial smooth minimum (k = smoothness) of
    the 125 cells' distances folded in z, y, x order, colour and position carried along."""
    base = np.floor(q).astype(int)
    blend = None
    for k in range(-2, 3):
        for j in range(-2, 3):
            for i in range(-2, 3):
                cell = tuple(base + (i, j, k))
                hashed = _reference_hash(flavour, cell)
                point = np.array((i, j, k)) + hashed * randomness
                d = float(_distance(metric, (point - (q - base))[None], exponent)[0])
                if blend is None:
                    blend = [d, hashed.copy(), point.copy()]
                    continue
                t = np.clip(0.5 + 0.5 * (blend[0] - d) / smoothness, 0.0, 1.0)
                h = t * t * (3 - 2 * t)
                rounding = smoothness * h * (1 - h)
                blend[0] = blend[0] + (d - blend[0]) * h - rounding
                rounding /= 1 + 3 * smoothness
                blend[1] = blend[1] + (hashed - blend[1]) * h - rounding
                blend[2] = blend[2] + (point - blend[2]) * h - rounding
    return blend[0], blend[1], blend[2] + base


@pytest.mark.parametrize("metric", ("EUCLIDEAN", "CHEBYCHEV"))
def test_smooth_f1_is_the_smooth_minimum_below_f1_and_f1_at_smoothness_zero(metric):
    """Smooth F1 against the smooth minimum folded here; it never exceeds F1 (a smooth
    minimum lies below the minimum), comes within its rounding of it, and at Smoothness 0
    is F1 itself."""
    rng = np.random.default_rng(13)
    m, scale = METRICS.index(metric), 2.0
    for p in rng.uniform(-3.0, 3.0, size=(25, 3)):
        for flavour in (HASH_LOOKUP3, HASH_PCG):
            args = (tuple(p), scale, 0.0, 0.5, 2.0, 0.9, 1.0)
            smooth = voronoi_texture(*args, 2, m, False, flavour, 0.6)
            d, colour, point = _smooth_reference(p * scale, flavour, 0.9, metric, 1.0, 0.3)
            assert math.isclose(smooth[0], d, rel_tol=1e-9, abs_tol=1e-12)
            np.testing.assert_allclose(smooth[1], colour, rtol=1e-9, atol=1e-12)
            np.testing.assert_allclose(smooth[2], point / scale, rtol=1e-9, atol=1e-12)
            f1 = voronoi_texture(*args, 0, m, False, flavour, 0.6)
            assert f1[0] - 0.3 <= smooth[0] <= f1[0] + 1e-12
            assert voronoi_texture(*args, 2, m, False, flavour, 0.0) == f1
