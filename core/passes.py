"""Render passes: what each one holds, where the kernels write it, and Cryptomatte's ids.

A render always makes Combined (RGBA). Asked for by name (`RenderSettings.passes`), the
kernels also write, per pixel, from the same camera rays:

    depth           1  distance of the nearest hit along the camera's view axis; 1e10 where
                       no camera ray of the pixel met anything (Blender's Z convention)
    mist            1  0 at the mist's start to 1 at start + depth, shaped by its falloff;
                       1 where a ray meets nothing; averaged over the pixel's rays
    normal          3  world-space shading normal facing the camera, averaged (not renormalised:
                       edges carry the coverage, as Cycles' does); 0 where nothing was met
    position        3  world-space point of the nearest hit; 0 where nothing was met
    uv              3  texture coordinates u, v of the surface, averaged, and the coverage
    object_index    1  Object > Relations > Pass Index of the nearest hit's object
    material_index  1  Material > Settings > Pass Index of the nearest hit's material
    diffuse_color   3  the diffuse reflectance at the first hit, times its opacity
                       (1 - transparency)
    shadow          3  share of the direct light reaching the first hit that its shadow rays
                       let through: 1 lit, 0 in full shadow, 1 where no light falls or nothing
                       was met
    environment     3  the background seen directly by camera rays
    ambient         3  ambient light at the first hit (kd * ambient)
    diffuse         3  direct diffuse light at the first hit, shadows included
    specular        3  highlights (Phong's, a node material's glints) at the first hit,
                       shadows included
    reflection      3  everything seen in the first hit's mirror reflection (and a dielectric's
                       Fresnel reflection), with all its own bounces
    refraction      3  everything seen through the first hit (its refracted ray and bounces)
    emission        3  the light the first hit emits itself (`Material.emission`)
    crypto_object   4 per 2 levels   Cryptomatte: per rank, (object id, coverage), by coverage
    crypto_material 4 per 2 levels   the same for materials

environment + ambient + diffuse + specular + reflection + refraction + emission = Combined's
RGB.

Averaging makes no sense for depth, position and the indices (the mean of two objects'
indices names a third, the mean of two depths lies in mid air): those are the nearest hit's
among the pixel's camera rays, as a Z-buffer keeps; the anti-aliased object masks are
Cryptomatte's. A holdout object (`Shape.holdout`) is a hole in all of them, as the
background is, but for mist and shadow (1) and the environment (0).
"""

from __future__ import annotations

import json
import math
import struct

import numpy as np

from .errors import SceneError
from .vocabulary import PASS_NAMES, PASS_SLOT

# Channels of each pass, in the kernels' order (core.vocabulary.PASS_NAMES)
PASS_CHANNELS = {
    "depth": 1,
    "mist": 1,
    "normal": 3,
    "position": 3,
    "uv": 3,
    "object_index": 1,
    "material_index": 1,
    "diffuse_color": 3,
    "shadow": 3,
    "environment": 3,
    "ambient": 3,
    "diffuse": 3,
    "specular": 3,
    "reflection": 3,
    "refraction": 3,
    "emission": 3,
    "crypto_object": 0,  # 4 per two levels: see channels()
    "crypto_material": 0,
}
assert tuple(PASS_CHANNELS) == PASS_NAMES
PASS_COUNT = len(PASS_NAMES)
CRYPTO_PASSES = ("crypto_object", "crypto_material")
# The terms that sum to Combined's RGB
TERMS = ("environment", "ambient", "diffuse", "specular", "reflection", "refraction", "emission")
# Blender's default (View Layer > Passes > Cryptomatte > Levels) and its range
DEFAULT_CRYPTO_LEVELS = 6
MAX_CRYPTO_LEVELS = 16
# Blender's Z for a pixel that met nothing
BACKGROUND_DEPTH = 1e10

# Mist falloffs, as Blender names them, and the power of the linear ramp each applies
MIST_FALLOFFS = {"QUADRATIC": 2.0, "LINEAR": 1.0, "INVERSE_QUADRATIC": 0.5}


def channels(name: str, crypto_levels: int = DEFAULT_CRYPTO_LEVELS) -> int:
    """How many float channels pass `name` has: a Cryptomatte pass has 4 per two levels
    (id and coverage of two ranks), rounded up as Blender rounds its CryptoObject00.. passes."""
    if name in CRYPTO_PASSES:
        return 4 * ((crypto_levels + 1) // 2)
    return PASS_CHANNELS[name]


def check_passes(owner: str, passes) -> tuple[str, ...]:
    """The pass names as a tuple, each known and given once."""
    try:
        names = tuple(passes)
    except TypeError:
        raise SceneError(owner, "passes", f"got {passes!r}; give a list of pass names") from None
    for name in names:
        if name not in PASS_CHANNELS:
            raise SceneError(
                owner, "passes", f"unknown pass {name!r}; use any of {', '.join(PASS_NAMES)}"
            )
    if len(set(names)) != len(names):
        raise SceneError(owner, "passes", f"got {list(names)}; name each pass once")
    return names


def layout(passes: tuple[str, ...], crypto_levels: int) -> tuple[np.ndarray, int]:
    """(offset of each pass slot in the channels after RGBA, -1 when not asked for; the
    number of those channels). The kernels write pass `p` at out[..., 4 + offset[p]]."""
    offsets = np.full(PASS_COUNT, -1, np.int64)
    total = 0
    for name in PASS_NAMES:  # in slot order, whatever order they were asked in
        if name in passes:
            offsets[PASS_SLOT[name]] = total
            total += channels(name, crypto_levels)
    return offsets, total


def split(pixels: np.ndarray, passes: tuple[str, ...], crypto_levels: int) -> dict:
    """The passes of a rendered (h, w, 4 + channels) array, each as a view (h, w, c)."""
    offsets, _ = layout(passes, crypto_levels)
    found = {}
    for name in passes:
        start = 4 + int(offsets[PASS_SLOT[name]])
        found[name] = pixels[..., start : start + channels(name, crypto_levels)]
    return found


# --- Cryptomatte ids: MurmurHash3 (x86, 32 bit, seed 0) of the name, as a float32 ---------


def murmur3_32(data: bytes, seed: int = 0) -> int:
    """MurmurHash3_x86_32, the hash the Cryptomatte specification names."""
    c1, c2, mask = 0xCC9E2D51, 0x1B873593, 0xFFFFFFFF
    h = seed & mask
    whole = len(data) // 4 * 4
    for (k,) in struct.iter_unpack("<I", data[:whole]):
        k = (k * c1) & mask
        k = ((k << 15) | (k >> 17)) & mask
        k = (k * c2) & mask
        h ^= k
        h = ((h << 13) | (h >> 19)) & mask
        h = (h * 5 + 0xE6546B64) & mask
    tail = data[whole:]
    if tail:
        k = int.from_bytes(tail, "little")
        k = (k * c1) & mask
        k = ((k << 15) | (k >> 17)) & mask
        k = (k * c2) & mask
        h ^= k
    h ^= len(data)
    h ^= h >> 16
    h = (h * 0x85EBCA6B) & mask
    h ^= h >> 13
    h = (h * 0xC2B2AE35) & mask
    h ^= h >> 16
    return h


def name_hash(name: str) -> int:
    return murmur3_32(name.encode("utf-8"))


def hash_to_float(h: int) -> float:
    """The specification's uint32 -> float32: the hash's bits as a float, its exponent moved
    off 0 and 255 so that it is never a denormal, infinity or NaN."""
    exponent = (h >> 23) & 0xFF
    if exponent in (0, 255):
        h ^= 1 << 23
    return struct.unpack("<f", struct.pack("<I", h))[0]


def crypto_id(name: str) -> float:
    """The float32 id a Cryptomatte pass holds for an object or material named `name`."""
    value = hash_to_float(name_hash(name))
    assert math.isfinite(value)
    return value


def manifest(names) -> str:
    """The JSON manifest, name -> the hash in 8 hex digits (before the float conversion,
    as Blender writes it)."""
    return json.dumps({name: f"{name_hash(name):08x}" for name in sorted(set(names))})


def crypto_metadata(layer_name: str, names) -> dict[str, str]:
    """The metadata a compositor looks for beside the passes of Cryptomatte layer
    `layer_name` (e.g. "ViewLayer.CryptoObject"): its keys are "cryptomatte/<first 7 hex
    digits of the layer name's hash>/name, hash, conversion, manifest"."""
    prefix = f"cryptomatte/{name_hash(layer_name):08x}"[:19] + "/"
    return {
        prefix + "name": layer_name,
        prefix + "hash": "MurmurHash3_32",
        prefix + "conversion": "uint32_to_float32",
        prefix + "manifest": manifest(names),
    }


def crypto_mask(pass_pixels: np.ndarray, name: str) -> np.ndarray:
    """A name's matte from a Cryptomatte pass (h, w, 2 * ranks): the sum of the coverages
    whose id is the name's, as a compositor's Cryptomatte node reads it."""
    ids, coverage = pass_pixels[..., 0::2], pass_pixels[..., 1::2]
    return np.where(ids == np.float32(crypto_id(name)), coverage, 0.0).sum(axis=-1)


def crypto_names(scene) -> dict[str, list[str]]:
    """The names each Cryptomatte pass can hold, for its manifest: the scene's objects
    (a CSG tree's is its top node's) and every material, CSG operands' included."""
    objects, materials = scene.object_and_material_names()
    return {"crypto_object": objects, "crypto_material": materials}
