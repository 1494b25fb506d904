"""The command line's pass files: one OpenEXR file per pass beside the PNG, named
`<picture>.<pass>.exr` (`final.depth.exr`), float channels as compositors expect them: R, G, B
for colours and vectors, Y for a single value, and Cryptomatte's CryptoObject00.R.. with its
manifest in the header, so Nuke's or Blender's Cryptomatte node reads the file as it is."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from .exr import write_exr
from .passes import CRYPTO_PASSES, crypto_metadata

CRYPTO_LAYERS = {"crypto_object": "CryptoObject", "crypto_material": "CryptoMaterial"}


def pass_file(picture: Path, name: str) -> Path:
    return picture.with_name(f"{picture.stem}.{name}.exr")


def pass_channels(name: str, values: np.ndarray) -> dict[str, np.ndarray]:
    """The file channels of pass `name` (values (h, w, c), row 0 at the top)."""
    if name in CRYPTO_PASSES:
        layer = CRYPTO_LAYERS[name]
        return {
            f"{layer}{c // 4:02d}.{'RGBA'[c % 4]}": values[..., c] for c in range(values.shape[2])
        }
    if values.shape[2] == 1:
        return {"Y": values[..., 0]}
    return {letter: values[..., c] for c, letter in enumerate("RGB")}


def write_pass_files(picture: Path, passes: dict[str, np.ndarray], names: dict) -> list[Path]:
    """Write each pass's file beside `picture`; `names` are what each Cryptomatte pass can
    hold (core.passes.crypto_names), for its manifest. Returns the files written."""
    written = []
    for name, values in passes.items():
        metadata = None
        if name in CRYPTO_PASSES:
            metadata = crypto_metadata(CRYPTO_LAYERS[name], names[name])
        written.append(write_exr(pass_file(picture, name), pass_channels(name, values), metadata))
    return written
