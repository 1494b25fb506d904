"""The Blackbody node's colour (core.blackbody, core.kernels.blackbody) against the CIE's own
figures for Planck's locus, the definition of luminance, and the integral itself. That the
colours are Cycles' is tests/blender/test_cycles_textures.py's check."""

import math

import numpy as np
import pytest

from core.blackbody import COLDEST_K, HOTTEST_K, blackbody_rec709, rec709_to_xyz
from core.kernels.blackbody import blackbody_colour


def _xy(rgb):
    x, y, z = rec709_to_xyz() @ rgb
    return x / (x + y + z), y / (x + y + z)


@pytest.mark.parametrize(
    ("kelvin", "expected"),
    [
        (2856.0, (0.44757, 0.40745)),  # CIE standard illuminant A: a black body at 2856 K
        (5000.0, (0.3451, 0.3516)),  # Planck's locus (CIE 015), to its 4 published places
        (6500.0, (0.3135, 0.3236)),
    ],
)
def test_the_colour_lies_on_plancks_locus_where_the_cie_places_it(kelvin, expected):
    x, y = _xy(blackbody_rec709(kelvin))
    assert x == pytest.approx(expected[0], abs=1.5e-4)
    assert y == pytest.approx(expected[1], abs=1.5e-4)


def test_the_matrix_takes_rec709_white_to_d65_and_the_colour_has_luminance_1():
    x, y, z = rec709_to_xyz() @ np.ones(3)
    assert (x / (x + y + z), y / (x + y + z)) == pytest.approx((0.3127, 0.3290), abs=1e-12)
    assert y == pytest.approx(1.0, abs=1e-12)
    for kelvin in (900.0, 1800.0, 4000.0, 9000.0):
        assert (rec709_to_xyz() @ blackbody_rec709(kelvin))[1] == pytest.approx(1.0, abs=1e-12)


def test_the_kernels_lookup_follows_the_integral_clamped_as_cycles_clamps():
    """Within 3e-5 of the integral over 800..12000 K; held at the ends beyond them (NaN
    as the coldest); negatives (blue below about 2000 K) clamped to 0."""
    worst = 0.0
    for kelvin in np.geomspace(COLDEST_K, HOTTEST_K, 997):
        exact = np.maximum(blackbody_rec709(kelvin), 0.0)
        worst = max(worst, float(np.abs(np.array(blackbody_colour(kelvin)) - exact).max()))
    assert worst < 3e-5, worst
    assert blackbody_colour(500.0) == blackbody_colour(COLDEST_K)
    assert blackbody_colour(math.nan) == blackbody_colour(COLDEST_K)
    assert blackbody_colour(40000.0) == blackbody_colour(HOTTEST_K)
    assert blackbody_rec709(1000.0)[2] < 0.0 and blackbody_colour(1000.0)[2] == 0.0
    warm, cool = blackbody_colour(2000.0), blackbody_colour(10000.0)
    assert warm[0] > warm[2] and cool[2] > cool[0]
