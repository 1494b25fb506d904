"""Building the packed arrays: fixed dtype and rank, whatever the scene (an empty table too),
so that the kernels compile once."""

from __future__ import annotations

import numpy as np


def rows(values, width: int = 3) -> np.ndarray:
    """(n, width) float64, also for n = 0."""
    return np.array(values, float).reshape(-1, width)


def concatenated(parts: list, shape: tuple, dtype) -> np.ndarray:
    """The parts one after another, or an empty array of `shape` when there are none."""
    if not parts:
        return np.zeros(shape, dtype)
    return np.ascontiguousarray(np.concatenate(parts), dtype)
