"""The sample scenes' textures, drawn here from formulas (numpy, Pillow; no Blender, no
downloaded assets). `python sample_blends/textures.py` rewrites them; the same seed gives the
same PNGs byte for byte."""

from __future__ import annotations

from pathlib import Path

import numpy as np
from PIL import Image

FOLDER = Path(__file__).resolve().parent / "textures"


def _value_noise(size: int, cells: int, rng: np.random.Generator) -> np.ndarray:
    """Smooth noise in [0, 1] on a size x size grid: random values on a periodic
    cells x cells lattice, blended with a smoothstep (so the texture tiles seamlessly)."""
    lattice = rng.random((cells, cells))
    coords = np.arange(size) * cells / size
    i0 = np.floor(coords).astype(int)
    f = coords - i0
    f = f * f * (3.0 - 2.0 * f)
    i1 = (i0 + 1) % cells
    rows0, rows1 = lattice[i0], lattice[i1]
    fy = f[:, None]
    top = rows0[:, i0] * (1.0 - f) + rows0[:, i1] * f
    bottom = rows1[:, i0] * (1.0 - f) + rows1[:, i1] * f
    return top * (1.0 - fy) + bottom * fy


def _fractal_noise(size: int, rng: np.random.Generator, octaves: int = 4) -> np.ndarray:
    total = np.zeros((size, size))
    for octave in range(octaves):
        total += _value_noise(size, 4 * 2**octave, rng) / 2**octave
    return total / (2.0 - 2.0 ** (1 - octaves))


def _mix(light, dark, t):
    """Colours light..dark by t in [0, 1] per pixel, as uint8 RGB."""
    light, dark = np.asarray(light, float), np.asarray(dark, float)
    rgb = light + (dark - light) * t[..., None]
    return np.clip(np.rint(rgb), 0, 255).astype(np.uint8)


def wood(size=512, light=(196, 142, 88), dark=(122, 74, 38), rings=9.0, seed=1) -> np.ndarray:
    """Planks of flat-sawn wood: growth rings around a trunk axis running along the image's
    x axis, warped by noise, with a finer grain."""
    rng = np.random.default_rng(seed)
    y, x = np.mgrid[0:size, 0:size] / size
    warp = _fractal_noise(size, rng)
    grain = _fractal_noise(size, rng, octaves=5)
    # Distance from a trunk axis along x that wanders a little: rings run the board's length
    distance = np.abs(y - 0.5 - 0.08 * np.sin(2 * np.pi * x)) * 2.0 + 0.2 * warp
    ring = 0.5 + 0.5 * np.sin(2 * np.pi * rings * distance)
    ring = ring**3  # thin dark latewood, wide light earlywood
    streaks = 0.5 + 0.5 * np.sin(2 * np.pi * (24 * y + 3 * grain))
    return _mix(light, dark, 0.75 * ring + 0.15 * streaks + 0.1 * grain)


def waffle(size=256, cells=8, dough=(214, 160, 90), groove=(150, 96, 44)) -> np.ndarray:
    """A waffle cone's diamond grid: grooves along both diagonals, raised squares between."""
    y, x = np.mgrid[0:size, 0:size] / size * cells
    a, b = (x + y) % 1.0, (x - y) % 1.0
    depth = np.maximum(np.exp(-(((a - 0.5) / 0.09) ** 2)), np.exp(-(((b - 0.5) / 0.09) ** 2)))
    bake = 0.12 * np.sin(np.pi * a) * np.sin(np.pi * b)  # browner at the square's rim
    return _mix(dough, groove, np.clip(depth + 0.3 - bake * 2.5, 0.0, 1.0))


def uv_grid(size=256, cells=8) -> np.ndarray:
    """A checker whose hue follows u and brightness follows v, so a texture's orientation and
    seams are visible on every primitive."""
    y, x = np.mgrid[0:size, 0:size] / size
    v = 1.0 - y  # v = 0 is the image's bottom row
    hue = np.floor(x * cells) / cells
    check = (np.floor(x * cells) + np.floor(v * cells)) % 2
    phase = 2 * np.pi * hue
    rgb = 0.5 + 0.45 * np.stack([np.cos(phase), np.cos(phase - 2.1), np.cos(phase + 2.1)], axis=-1)
    brightness = (0.45 + 0.55 * (np.floor(v * cells) + 1) / cells) * (0.55 + 0.45 * check)
    return np.clip(np.rint(255 * rgb * brightness[..., None]), 0, 255).astype(np.uint8)


def checker(size=256, cells=8, first=(235, 235, 235), second=(40, 40, 40)) -> np.ndarray:
    y, x = np.mgrid[0:size, 0:size] * cells // size
    odd = ((x + y) % 2).astype(bool)
    return np.where(odd[..., None], np.array(second, np.uint8), np.array(first, np.uint8))


TEXTURES = {
    "wood_table.png": lambda: wood(seed=1),
    "wood_floor.png": lambda: wood(light=(170, 118, 72), dark=(96, 58, 30), rings=6.0, seed=2),
    "waffle.png": waffle,
    "uv_grid.png": uv_grid,
    "checker.png": checker,
}


def write_all(folder: Path = FOLDER) -> list[Path]:
    folder.mkdir(parents=True, exist_ok=True)
    paths = []
    for name, draw in TEXTURES.items():
        path = folder / name
        Image.fromarray(draw(), "RGB").save(path, optimize=True)
        paths.append(path)
    return paths


if __name__ == "__main__":
    for written in write_all():
        print(written)
