"""The Noise texture's parts (core.kernels.noise) against what must hold of them whatever
the hash: Perlin noise vanishes at every lattice point and is continuous across cells;
one octave, normalised, is 0.5 + 0.5 x the signed noise; a fractional Detail mixes in
the next octave linearly; the offsets written out in the module are the hash's own.
Blender's own values are matched in tests/blender/test_cycles_textures.py (every pixel
within 0.003 of Cycles', in 3.4, 4.2 and 5.2)."""

import numpy as np
import pytest

from core.kernels.noise import OFFSETS, fbm, perlin_3d, random_offset, signed_noise


def test_perlin_noise_vanishes_at_the_lattice_points():
    rng = np.random.default_rng(2)
    for x, y, z in rng.integers(-50, 50, size=(40, 3)):
        assert perlin_3d(float(x), float(y), float(z)) == 0.0


def test_perlin_noise_is_continuous_across_cell_faces():
    rng = np.random.default_rng(3)
    for y, z in rng.uniform(-20, 20, size=(40, 2)):
        x = float(rng.integers(-20, 20))
        below, above = perlin_3d(x - 1e-9, y, z), perlin_3d(x + 1e-9, y, z)
        assert abs(below - above) < 1e-7


def test_one_octave_normalised_is_half_the_signed_noise_plus_a_half():
    p = (0.37, -1.21, 4.05)
    assert fbm(p, 0.0, 0.5, 2.0, True) == pytest.approx(0.5 * signed_noise(p) + 0.5, abs=1e-15)
    assert fbm(p, 0.0, 0.5, 2.0, False) == pytest.approx(signed_noise(p), abs=1e-15)


def test_a_fractional_detail_mixes_the_next_octave_in_linearly():
    p = (1.3, 0.2, -0.7)
    whole, next_ = fbm(p, 2.0, 0.6, 2.1, True), fbm(p, 3.0, 0.6, 2.1, True)
    assert fbm(p, 2.25, 0.6, 2.1, True) == pytest.approx(0.75 * whole + 0.25 * next_, abs=1e-12)


def test_the_written_out_offsets_are_the_hashs():
    for seed, written in enumerate(OFFSETS):
        assert random_offset(float(seed)) == written
        assert all(100.0 <= v <= 200.0 for v in written)


def test_the_factor_is_the_same_whether_or_not_the_colour_is_made():
    """A graph that reads only Fac skips the Color's two extra fractal sums."""
    from core.kernels.noise import noise_texture

    p = (2.3, -0.4, 1.1)
    with_colour = noise_texture(p, 2.5, 0.5, 2.0, 0.3, True, True)
    without = noise_texture(p, 2.5, 0.5, 2.0, 0.3, True, False)
    assert with_colour[0] == without[0] == with_colour[1][0]
    assert with_colour[1][1] != with_colour[0]  # the colour's own channels
