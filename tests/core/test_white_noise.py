"""White Noise (core.kernels.white_noise): the float32 bit patterns it hashes against
numpy's own view of the same float32 numbers, and its 3D colour of whole-number cells
against the Voronoi texture's cell hash (Cycles' same hash_float3_to_float3, compared
with Cycles in tests/blender/test_cycles_textures.py). Compared with Cycles pixel by pixel
in tests/blender/test_cycles_value_nodes.py."""

import numpy as np
import pytest

from core.kernels.voronoi import HASH_LOOKUP3, cell_hash
from core.kernels.white_noise import float32_bits, white_noise


def test_the_bits_are_those_of_the_float32_number():
    rng = np.random.default_rng(61)
    values = np.concatenate([
        rng.normal(scale=10.0 ** rng.uniform(-40, 30, 400)),
        [0.0, -0.0, 1.0, -2.5, 3.0e38, 1e-45, -7e-42, 1.1754942e-38, np.inf, -np.inf],
    ])  # fmt: skip
    for x in values:
        expected = int(np.array([x], np.float32).view(np.uint32)[0])
        assert float32_bits(float(x)) == expected, x


@pytest.mark.parametrize("cell", [(0, 0, 0), (3, -2, 7), (-15, 40, -1), (1000, 1, -999)])
def test_white_noise_of_a_whole_cell_is_the_voronoi_cell_hash(cell):
    value, colour = white_noise(3, tuple(float(c) for c in cell), 0.0)
    expected = cell_hash(HASH_LOOKUP3, *cell)
    assert value == expected[0]
    np.testing.assert_array_equal(colour, expected)


def test_each_dimension_reads_its_own_inputs():
    p, w = (1.0, 2.0, 3.0), 4.0
    assert white_noise(1, (9.0, 9.0, 9.0), w) == white_noise(1, p, w)  # W alone
    assert white_noise(2, (1.0, 2.0, 9.0), 7.0) == white_noise(2, p, w)  # x and y
    assert white_noise(3, p, 7.0) == white_noise(3, p, w)  # the vector
    assert white_noise(4, p, 7.0) != white_noise(4, p, w)  # and W
