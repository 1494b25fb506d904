"""A small equirectangular sky for the tests and benchmarks of the environment."""

import numpy as np


def sky(height=64):
    """A blue gradient above, brown ground below, brighter towards +X, and a 3 x 3-pixel
    sun of radiance 400 about 40 degrees up (linear RGB, row 0 at the top)."""
    width = 2 * height
    theta = np.pi * (np.arange(height) + 0.5) / height
    phi = np.pi - 2 * np.pi * (np.arange(width) + 0.5) / width
    up = np.cos(theta)[:, None] * np.ones(width)
    towards_x = 1.0 + 0.5 * np.cos(phi)[None, :]
    pixels = np.where(
        (up > 0)[..., None],
        np.stack([0.3 + 0.2 * up, 0.5 + 0.2 * up, 1.0 + 0.0 * up], axis=-1),
        np.array([0.25, 0.18, 0.1]),
    )
    pixels = pixels * towards_x[..., None]
    sun_row = int(round(height * (0.5 - 40.0 / 180.0)))
    pixels[sun_row - 1 : sun_row + 2, width // 3 - 1 : width // 3 + 2] = 400.0
    return pixels
