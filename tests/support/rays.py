"""Camera rays for tests that compare masks or hits: a square grid aimed at the origin."""

import numpy as np


def rays_towards_origin(eye, size, half_extent):
    """(origins, unit directions) of a size x size grid of rays from `eye` towards the
    origin, spanning +-half_extent on the image plane at unit distance, z up, row 0 at the
    top."""
    eye = np.asarray(eye, float)
    forward = -eye / np.linalg.norm(eye)
    right = np.cross(forward, (0, 0, 1.0))
    right /= np.linalg.norm(right)
    up = np.cross(right, forward)
    s = np.linspace(-half_extent, half_extent, size)
    x, y = np.meshgrid(s, -s)
    d = (forward + x[..., None] * right + y[..., None] * up).reshape(-1, 3)
    return np.broadcast_to(eye, d.shape).copy(), d / np.linalg.norm(d, axis=1, keepdims=True)
