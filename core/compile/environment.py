"""The environment (`core.model.Environment`) as the arrays `core.kernels.environment` reads:
its colour, the Mapping's affine rows, the image's linear pixels, and the tables that pick a
pixel in proportion to how much light comes from it.

Importance: pixel (i, j), row i from the top, is picked with probability proportional to

    weight(i, j) = luminance the bilinear lookup gives over the pixel's square x sin(theta_i)

sin(theta_i) for the solid angle a pixel of row i spans. Over its square the lookup blends
the pixel with its eight neighbours, so every direction the image lights has a non-zero
chance (no bias); a floor of a millionth of the mean weight covers a black image. The
marginal table picks a row, the row's table a pixel, each a cumulative sum normalised to end
at 1.
"""

from __future__ import annotations

import numpy as np

from ..kernels.layout import (
    ENVIRONMENT_IMAGE,
    ENVIRONMENT_NONE,
    ENVIRONMENT_UNIFORM,
)
from ..model.environment import Environment
from ..textures import load_texture

# Rec. 709 luminance of linear RGB
LUMINANCE = np.array([0.2126, 0.7152, 0.0722])
WEIGHT_FLOOR = 1e-6


def environment_kind(environment: Environment | None) -> int:
    """OPTION_ENVIRONMENT: ENVIRONMENT_NONE for none or a black one (the background colour
    then shows, and nothing is sampled), else uniform or image."""
    if environment is None or environment.is_dark():
        return ENVIRONMENT_NONE
    return ENVIRONMENT_UNIFORM if environment.image is None else ENVIRONMENT_IMAGE


def pack_environment(environment: Environment | None) -> dict:
    """The Lights fields of the environment (env_*)."""
    kind = environment_kind(environment)
    if kind == ENVIRONMENT_NONE:
        return _arrays(np.zeros(3), np.eye(3, 4), np.zeros((0, 0, 3)))
    colour = np.asarray(environment.colour, float)
    transform = np.asarray(environment.direction_from_world, float)
    if kind == ENVIRONMENT_UNIFORM:
        return _arrays(colour, transform, np.zeros((0, 0, 3)))
    pixels = load_texture(environment.image, f"world '{environment.name}'")
    return _arrays(colour, transform, np.maximum(pixels, 0.0))


def _arrays(colour, transform, pixels: np.ndarray) -> dict:
    height, width = pixels.shape[:2]
    rows, columns = _tables(pixels, colour)
    # Importance sampling maps image directions back through the Mapping: exact for a
    # rotation only; any other Mapping lights by cosine-weighted directions instead
    linear, offset = transform[:, :3], transform[:, 3]
    rotation = np.allclose(linear @ linear.T, np.eye(3), atol=1e-9) and not np.any(offset)
    return {
        "env_colour": np.asarray(colour, float),
        "env_transform": np.ascontiguousarray(transform, float),
        "env_pixels": np.ascontiguousarray(pixels.reshape(-1, 3), np.float32),
        "env_size": np.array([width, height, int(rotation)], np.int64),
        "env_row_cdf": rows,
        "env_column_cdf": columns,
    }


def _tables(pixels: np.ndarray, colour) -> tuple[np.ndarray, np.ndarray]:
    """(the marginal table over rows (h + 1,), each row's table over its pixels (h, w + 1))."""
    height, width = pixels.shape[:2]
    if height == 0:
        return np.zeros(1), np.zeros((0, 1))
    luminance = (pixels.astype(float) * np.asarray(colour, float)) @ LUMINANCE
    # The bilinear lookup's light over each pixel's square: 3/4 of its own, 1/8 of each
    # neighbour's along each axis (the image repeats across its edges, as its lookup does)
    for axis in (0, 1):
        luminance = (
            0.75 * luminance
            + 0.125 * np.roll(luminance, 1, axis=axis)
            + 0.125 * np.roll(luminance, -1, axis=axis)
        )
    sin_theta = np.sin(np.pi * (np.arange(height) + 0.5) / height)
    weight = luminance * sin_theta[:, None]
    weight = np.maximum(weight, WEIGHT_FLOOR * max(weight.mean(), 1e-300))
    row_sums = weight.sum(axis=1)
    columns = np.zeros((height, width + 1))
    columns[:, 1:] = np.cumsum(weight, axis=1) / row_sums[:, None]
    columns[:, -1] = 1.0
    rows = np.zeros(height + 1)
    rows[1:] = np.cumsum(row_sums) / row_sums.sum()
    rows[-1] = 1.0
    return rows, columns
