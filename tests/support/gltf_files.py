"""Small glTF 2.0 files written by the tests (one .gltf, its buffer and PNG images embedded
as data URIs), so that Blender's own glTF importer makes the materials it makes of the
public sample models: no downloaded file in the repository."""

from __future__ import annotations

import base64
import io
import json
from pathlib import Path

import numpy as np
from PIL import Image

# glTF's sampler filters and its buffer component types
NEAREST = 9728
FLOAT, UNSIGNED_SHORT = 5126, 5123


def checker(a, b, n: int = 4) -> np.ndarray:
    """(n, n, 3) uint8: an n x n checker of colours a and b (0..255)."""
    rows, columns = np.indices((n, n))
    return np.where(((rows + columns) % 2 == 0)[..., None], np.array(a), np.array(b)).astype(
        np.uint8
    )


def _png(pixels: np.ndarray) -> str:
    out = io.BytesIO()
    Image.fromarray(pixels).save(out, "PNG")
    return "data:image/png;base64," + base64.b64encode(out.getvalue()).decode()


def _data(blob: bytes) -> str:
    return "data:application/octet-stream;base64," + base64.b64encode(blob).decode()


def write_quad(path: Path, material: dict, images: list, half_size: float = 10.0,
               colors=None) -> Path:  # fmt: skip
    """A glTF file of one square, 2 half_size across, in glTF's y = 0 plane facing +Y (z = 0
    facing up once Blender's importer turns Y-up into Z-up), UVs (0, 0) to (1, 1), with
    `material` (a glTF material object; its textures index `images`, uint8 RGB arrays,
    sampled nearest) on it, and `colors` (4 linear RGBA, one a corner) as its COLOR_0 if
    given. The object and mesh are named "Quad"."""
    s = half_size
    positions = np.array([[-s, 0, s], [s, 0, s], [s, 0, -s], [-s, 0, -s]], np.float32)
    normals = np.tile(np.array([[0, 1, 0]], np.float32), (4, 1))
    uvs = np.array([[0, 1], [1, 1], [1, 0], [0, 0]], np.float32)  # glTF's v runs down
    indices = np.array([0, 1, 2, 0, 2, 3], np.uint16)
    parts = [positions.tobytes(), normals.tobytes(), uvs.tobytes(), indices.tobytes()]
    if colors is not None:
        parts.append(np.asarray(colors, np.float32).reshape(4, 4).tobytes())
    offsets = np.cumsum([0, *map(len, parts)])
    blob = b"".join(parts)
    views = [dict(buffer=0, byteOffset=int(offsets[k]), byteLength=len(part))
             for k, part in enumerate(parts)]  # fmt: skip
    accessors = [
        dict(bufferView=0, componentType=FLOAT, count=4, type="VEC3",
             min=positions.min(0).tolist(), max=positions.max(0).tolist()),
        dict(bufferView=1, componentType=FLOAT, count=4, type="VEC3"),
        dict(bufferView=2, componentType=FLOAT, count=4, type="VEC2"),
        dict(bufferView=3, componentType=UNSIGNED_SHORT, count=6, type="SCALAR"),
    ]  # fmt: skip
    if colors is not None:
        accessors.append(dict(bufferView=4, componentType=FLOAT, count=4, type="VEC4"))
    primitive = dict(attributes=dict(POSITION=0, NORMAL=1, TEXCOORD_0=2), indices=3, material=0)
    if colors is not None:
        primitive["attributes"]["COLOR_0"] = 4
    gltf = dict(
        asset=dict(version="2.0"),
        scene=0,
        scenes=[dict(nodes=[0])],
        nodes=[dict(mesh=0, name="Quad")],
        meshes=[dict(name="Quad", primitives=[primitive])],
        materials=[material],
        textures=[dict(source=k, sampler=0) for k in range(len(images))],
        samplers=[dict(magFilter=NEAREST, minFilter=NEAREST)],
        images=[dict(uri=_png(pixels)) for pixels in images],
        buffers=[dict(byteLength=len(blob), uri=_data(blob))],
        bufferViews=views,
        accessors=accessors,
    )  # fmt: skip
    path.write_text(json.dumps(gltf))
    return path


def import_gltf(bpy, path: Path) -> None:
    """Blender's own importer (its bundled add-on, enabled if it is not)."""
    import addon_utils

    addon_utils.enable("io_scene_gltf2", default_set=True, handle_error=None)
    bpy.ops.import_scene.gltf(filepath=str(path))
