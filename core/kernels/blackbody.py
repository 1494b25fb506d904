"""The Blackbody node's colour in a kernel: core.blackbody's table (linear Rec.709 of
luminance 1, rows evenly spaced in reciprocal temperature from 800 K to 12000 K) looked up
linearly, the temperature held within that range, negatives clamped, as Cycles does."""

import numpy as np

from ..blackbody import COLDEST_K, HOTTEST_K, blackbody_table
from ..jit.decorators import kernel

# A global array: numba freezes it into the compiled kernel as a constant
BLACKBODY_TABLE = np.ascontiguousarray(blackbody_table())
_LAST = BLACKBODY_TABLE.shape[0] - 1
_INVERSE_COLDEST, _INVERSE_HOTTEST = 1.0 / COLDEST_K, 1.0 / HOTTEST_K


@kernel
def blackbody_colour(kelvin):
    """(r, g, b) of a black body at `kelvin` (NaN or below 800 K: 800 K's colour)."""
    if not kelvin > COLDEST_K:
        kelvin = COLDEST_K
    kelvin = min(kelvin, HOTTEST_K)
    x = (_INVERSE_COLDEST - 1.0 / kelvin) / (_INVERSE_COLDEST - _INVERSE_HOTTEST) * _LAST
    row = min(int(x), _LAST - 1)
    t = x - row
    a, b = BLACKBODY_TABLE[row], BLACKBODY_TABLE[row + 1]
    return (max((1.0 - t) * a[0] + t * b[0], 0.0), max((1.0 - t) * a[1] + t * b[1], 0.0),
            max((1.0 - t) * a[2] + t * b[2], 0.0))  # fmt: skip
