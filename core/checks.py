"""Argument checks shared by the scene model: each raises `SceneError` naming owner and field."""

from __future__ import annotations

import math
import os

import numpy as np

from .errors import SceneError

# An RGB colour, a point or a direction, as the scene model's fields take it
Vec3 = tuple[float, float, float]

# A transform whose smallest singular value is below this fraction of its largest squashes
# the shape flat: the inverse needed for object-space intersection would be meaningless.
SINGULAR_RATIO = 1e-12
# The shortest direction vector accepted: normalising anything shorter underflows
MIN_LENGTH = 1e-150
# The brightest light a scene may hold (a light's power, a World's radiance): the kernels
# carry light in float32, whose largest value is 3.4e38, and multiply it by factors of many
# sizes on the way to a pixel; a World of 1e76 (Color x Strength at Blender's largest) gave a
# white frame. The sun is 1e3 W/m^2, its disc 2e7 W/m^2/sr: 1e20 leaves room for any scene
MAX_LIGHT = 1e20
# The farthest a shape may reach from the origin, in scene units: the kernels intersect in
# each shape's own space, and a sphere of radius 1e308 around the camera, scaled down by
# 1e-308, left rays of length 1e-308 whose squares vanish: it was not drawn at all. 1e30
# keeps every square and product within float64, and boxes within float32
MAX_EXTENT = 1e30


def check_number(owner: str, name: str, value, low=None, high=None, low_open=False) -> float:
    """A finite real number in [low, high] (or (low, high] with low_open)."""
    valid = _range_text(low, high, low_open)
    if isinstance(value, bool) or not isinstance(value, (int, float, np.number)):
        raise SceneError(owner, name, f"got {value!r}; use {valid}")
    if not math.isfinite(value):
        raise SceneError(owner, name, f"got {value!r}; use {valid} (finite)")
    too_low = low is not None and (value <= low if low_open else value < low)
    if too_low or (high is not None and value > high):
        raise SceneError(owner, name, f"got {value!r}; use {valid}")
    return float(value)


def check_count(owner: str, name: str, value, low: int = 0, high: int | None = None) -> int:
    """A whole number >= low, and <= high if given."""
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or value < low:
        raise SceneError(owner, name, f"got {value!r}; use a whole number >= {low}")
    if high is not None and value > high:
        raise SceneError(owner, name, f"got {value!r}; use a whole number from {low} to {high}")
    return int(value)


def check_flag(owner: str, name: str, value) -> bool:
    if not isinstance(value, bool | np.bool_):
        raise SceneError(owner, name, f"got {value!r}; need True or False")
    return bool(value)


def check_choice(owner: str, name: str, value, choices: tuple[str, ...]) -> str:
    if value not in choices:
        raise SceneError(owner, name, f"got {value!r}; use one of {', '.join(choices)}")
    return value


def check_vec3(owner, name, value, nonnegative=False, nonzero=False, high=None) -> np.ndarray:
    try:
        v = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        raise SceneError(owner, name, f"got {value!r}; use three numbers") from None
    if v.shape != (3,):
        raise SceneError(owner, name, f"got {value!r}; use three numbers")
    if not np.all(np.isfinite(v)):
        raise SceneError(owner, name, f"got {value!r}; all three numbers must be finite")
    if nonnegative and np.any(v < 0):
        raise SceneError(owner, name, f"got {value!r}; each number must be >= 0")
    if high is not None and np.any(v > high):
        raise SceneError(owner, name, f"got {value!r}; each number must be at most {high:g}")
    # Squares below the smallest double vanish, so a length under 1e-150 computes as zero
    if nonzero and not np.linalg.norm(v) > MIN_LENGTH:
        raise SceneError(
            owner, name, f"got {value!r}; use a non-zero vector (length above {MIN_LENGTH})"
        )
    return v


def check_light(owner: str, name: str, value) -> np.ndarray:
    """A light's colour, power or radiance: three finite numbers from 0 to MAX_LIGHT."""
    return check_vec3(owner, name, value, nonnegative=True, high=MAX_LIGHT)


def valid_affine(matrices: np.ndarray) -> np.ndarray:
    """For (n, 4, 4) matrices, which are usable object-to-world transforms: finite, affine
    (bottom row 0 0 0 1) and not singular. Vectorised, for scenes of thousands of shapes."""
    ok = np.isfinite(matrices).all(axis=(1, 2))
    ok &= np.abs(matrices[:, 3] - (0.0, 0.0, 0.0, 1.0)).max(axis=1) <= 1e-8
    if ok.any():
        singular_values = np.linalg.svd(matrices[ok, :3, :3], compute_uv=False)
        ok[ok] = singular_values[:, -1] > SINGULAR_RATIO * singular_values[:, 0]
    return ok


def check_affine(owner: str, name: str, matrix) -> np.ndarray:
    m = np.asarray(matrix, dtype=float)
    if m.shape != (4, 4):
        raise SceneError(owner, name, f"got shape {m.shape}; use a 4x4 matrix")
    if valid_affine(m[None])[0]:
        return m
    if not np.all(np.isfinite(m)):
        raise SceneError(owner, name, "contains NaN or infinity; use finite numbers")
    if np.abs(m[3] - (0.0, 0.0, 0.0, 1.0)).max() > 1e-8:
        raise SceneError(owner, name, f"bottom row is {m[3]}; an affine matrix ends in 0 0 0 1")
    raise SceneError(
        owner,
        name,
        "is singular (a scale of zero along some axis flattens the shape); "
        "give every axis a non-zero scale",
    )


def check_array(owner: str, name: str, value, columns: int, kind: str) -> np.ndarray:
    """An (n, columns) array of finite numbers ('float') or integers ('int')."""
    try:
        a = np.asarray(value)
    except (TypeError, ValueError):
        raise SceneError(owner, name, f"use an (n, {columns}) array of numbers") from None
    if a.ndim != 2 or a.shape[1] != columns or a.dtype.kind not in "biuf":
        raise SceneError(owner, name, f"got shape {a.shape}; use an (n, {columns}) array")
    if kind == "int" and a.dtype.kind == "f":
        raise SceneError(owner, name, f"got {a.dtype} numbers; use whole-number indices")
    if a.dtype.kind == "f" and not np.all(np.isfinite(a)):
        bad = int(np.argwhere(~np.isfinite(a))[0][0])
        raise SceneError(owner, name, f"row {bad} has NaN or infinity; use finite numbers")
    return a


def _range_text(low, high, low_open) -> str:
    if low is None and high is None:
        return "a number"
    if high is None:
        return f"a number {'>' if low_open else '>='} {low}"
    if low is None:
        return f"a number <= {high}"
    return f"a number {'above' if low_open else 'from'} {low} to {high}"


def machine_memory() -> int | None:
    """This machine's physical memory in bytes, or None where the OS does not say."""
    try:
        return os.sysconf("SC_PAGE_SIZE") * os.sysconf("SC_PHYS_PAGES")
    except (AttributeError, ValueError, OSError):  # Windows has no sysconf
        return None
