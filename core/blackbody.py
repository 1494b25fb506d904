"""The colour of a black body at a temperature, as Blender's Blackbody node gives it: Planck's
spectrum seen by the CIE 1931 standard observer (core.cie_1931), in linear Rec.709 (Blender's
scene-linear space), scaled to luminance 1 — brightness is the Emission Strength's job.

Cycles evaluates a fit of the same curve between 800 K and 12000 K and holds its ends beyond
them, and clamps the negative components (the locus leaves Rec.709's gamut below about
2000 K, in blue). Integrating the spectrum here agrees with Cycles' fit to 0.0014 at every
temperature (3e-4 of the value; tests/blender/test_cycles_textures.py). The kernel looks the
colour up in BLACKBODY_TABLE, sampled evenly in reciprocal temperature, where the colour
changes evenly; linear interpolation between its rows is within 2e-5 of the integral."""

import numpy as np

from .cie_1931 import CMF_1931, STEP_NM, WAVELENGTHS_NM

COLDEST_K, HOTTEST_K = 800.0, 12000.0
# Planck's second radiation constant h c / k, in nm K (CODATA 2018)
_C2_NM_K = 1.438776877e7
# Rec.709's primaries and white (D65), as CIE xy chromaticities (ITU-R BT.709-6)
_PRIMARIES_XY = ((0.64, 0.33), (0.30, 0.60), (0.15, 0.06))
_WHITE_XY = (0.3127, 0.3290)
TABLE_ROWS = 512


def _xyz_of_xy(x, y):
    return np.array((x / y, 1.0, (1.0 - x - y) / y))


def rec709_to_xyz() -> np.ndarray:
    """The 3 x 3 matrix from linear Rec.709 to XYZ: the primaries' XYZ columns scaled so that
    (1, 1, 1) is the white point at luminance 1."""
    columns = np.stack([_xyz_of_xy(*xy) for xy in _PRIMARIES_XY], axis=1)
    return columns * np.linalg.solve(columns, _xyz_of_xy(*_WHITE_XY))


def planck_xyz(kelvin: float) -> np.ndarray:
    """XYZ of a black body's spectral radiance at `kelvin`, up to a constant factor (a
    Riemann sum over the 5 nm table)."""
    nm = WAVELENGTHS_NM
    radiance = nm**-5.0 / np.expm1(_C2_NM_K / (nm * kelvin))
    return (radiance[:, None] * CMF_1931).sum(axis=0) * STEP_NM


def blackbody_rec709(kelvin: float) -> np.ndarray:
    """The Blackbody node's colour at `kelvin` before Cycles' clamp of negatives: linear
    Rec.709 of luminance 1, the temperature held within COLDEST_K..HOTTEST_K as Cycles
    holds it."""
    kelvin = min(max(float(kelvin), COLDEST_K), HOTTEST_K)
    xyz = planck_xyz(kelvin)
    return np.linalg.solve(rec709_to_xyz(), xyz / xyz[1])


def blackbody_table(rows: int = TABLE_ROWS) -> np.ndarray:
    """(rows, 3): the colour at reciprocal temperatures evenly spaced from 1 / COLDEST_K
    (row 0) to 1 / HOTTEST_K (the last row)."""
    inverse = np.linspace(1.0 / COLDEST_K, 1.0 / HOTTEST_K, rows)
    return np.array([blackbody_rec709(1.0 / t) for t in inverse])
