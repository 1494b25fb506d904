"""The Magic texture (core.kernels.shader_values.magic) at depth 0, where it is three plain
waves in closed form, and its ranges at every depth. Compared with Cycles pixel by pixel
in tests/blender/test_cycles_value_nodes.py."""

import math

import numpy as np
import pytest

from core.kernels.shader_values import magic


@pytest.mark.parametrize("distortion", [1.0, 2.5, 0.0])
def test_at_depth_zero_magic_is_three_waves_of_the_coordinates_sums(distortion):
    rng = np.random.default_rng(61)
    for p in rng.uniform(-3.0, 3.0, (50, 3)):
        x = math.sin(5.0 * (p[0] + p[1] + p[2]))
        y = math.cos(5.0 * (-p[0] + p[1] - p[2]))
        z = -math.cos(5.0 * (-p[0] - p[1] + p[2]))
        divisor = 2.0 * distortion if distortion else 1.0
        expected = (0.5 - x / divisor, 0.5 - y / divisor, 0.5 - z / divisor)
        np.testing.assert_allclose(magic(tuple(p), 0, distortion), expected, atol=1e-12)


@pytest.mark.parametrize("depth", range(11))
def test_magic_stays_within_its_range_at_every_depth(depth):
    """Each wave is at most the distortion d in size, halved by 2d: the colour lies in
    0..1 (without distortion the depth's waves vanish: 0.5 - each first wave)."""
    rng = np.random.default_rng(depth)
    for p in rng.uniform(-3.0, 3.0, (50, 3)):
        colour = np.array(magic(tuple(p), depth, 1.3))
        assert np.all(colour >= -1e-12) and np.all(colour <= 1.0 + 1e-12)
