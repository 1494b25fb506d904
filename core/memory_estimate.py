"""What a render will need in memory, estimated before any of it is allocated.

A render that cannot fit is refused up front, with the figure and the setting to change,
rather than starting and being killed by the system half-way (or swapping the machine to a
standstill). The figures per item were measured here, as the peak resident memory over the
process's own while packing (Linux's VmHWM; numpy's and numba's allocations both count), with
a margin:
- a mesh triangle peaks at 560 bytes while its BVH is built, and holds 200 after (400,000
  random triangles: 224 MB);
- a texture pixel is held as float32 RGB (12 bytes) and passes through float64 RGB and the
  sRGB curve's temporaries (99 bytes in all, 4 million pixels: 396 MB) while it loads, one
  texture at a time;
- an image pixel is float32 RGBA (16 bytes), and Blender keeps a copy of its own;
- a shape's rows (transforms, bounds, the top-level BVH) are a few hundred bytes;
- each worker thread's ray stack holds max_depth + 2 rays of 80 bytes, and its shadow rays
  40 bytes a sample.
"""

from __future__ import annotations

import os
from dataclasses import dataclass

from .checks import machine_memory
from .errors import SceneError
from .model import Mesh, Texture

TRIANGLE_PEAK_BYTES = 700
TEXEL_BYTES, TEXEL_LOADING_BYTES = 12, 120
PIXEL_BYTES = 32  # the image and Blender's copy
SHAPE_BYTES = 500
RAY_BYTES, SHADOW_SAMPLE_BYTES = 80, 40
WORKSPACE_BYTES = 256 * 2**10  # the fixed stacks of one thread


@dataclass(frozen=True)
class MemoryEstimate:
    """Bytes by part, and what each part counts (for the message)."""

    parts: dict[str, int]
    counts: dict[str, str]

    @property
    def total(self) -> int:
        return sum(self.parts.values())


# The setting to change for each part, in the user's terms
REMEDIES = {
    "meshes": "use fewer or simpler meshes (a Decimate modifier, or instances of one mesh, "
    "which share its triangles)",
    "textures": "use smaller texture images",
    "image": "render it smaller, or in parts, a render border each",
    "shapes": "use fewer objects",
    "ray stacks": "lower Max Depth or Shadow Samples, or the thread count",
}


def estimate(shapes: list, settings) -> MemoryEstimate:
    """The estimate for these shapes (the scene's and its CSG operands) and settings."""
    threads = settings.threads or os.cpu_count() or 1
    triangles, texels, largest_texture = 0, 0, 0
    seen_meshes, seen_textures = set(), set()
    for shape in shapes:
        if isinstance(shape, Mesh) and id(shape.mesh) not in seen_meshes:
            seen_meshes.add(id(shape.mesh))
            triangles += len(shape.mesh.triangles)
        texture = shape.material.texture
        if texture is not None and id(texture) not in seen_textures:
            seen_textures.add(id(texture))
            size = texture_pixels(texture)
            texels += size
            largest_texture = max(largest_texture, size)
    pixels = settings.width * settings.height
    per_thread = (
        WORKSPACE_BYTES
        + (settings.max_depth + 2) * RAY_BYTES
        + settings.shadow_samples * SHADOW_SAMPLE_BYTES
    )
    parts = {
        "meshes": triangles * TRIANGLE_PEAK_BYTES,
        "textures": texels * TEXEL_BYTES + largest_texture * TEXEL_LOADING_BYTES,
        "image": pixels * PIXEL_BYTES,
        "shapes": len(shapes) * SHAPE_BYTES,
        "ray stacks": max(threads, 1) * per_thread,
    }
    counts = {
        "meshes": f"{triangles:,} triangles",
        "textures": f"{texels:,} pixels",
        "image": f"{settings.width} x {settings.height}",
        "shapes": f"{len(shapes):,}",
        "ray stacks": f"{max(threads, 1)} threads, max depth {settings.max_depth}",
    }
    return MemoryEstimate(parts, counts)


def texture_pixels(texture: Texture) -> int:
    """The texture's pixel count, from its array or its file's header (the pixels are not
    decoded); 0 if the file cannot be read, which loading it reports."""
    if texture.pixels is not None:
        shape = getattr(texture.pixels, "shape", ())
        return int(shape[0]) * int(shape[1]) if len(shape) >= 2 else 0
    from .textures import open_image  # Pillow: only when a texture names a file

    try:
        with open_image(texture.path) as image:
            width, height = image.size
    except Exception:  # noqa: BLE001 - any unreadable file is load_texture's to report
        return 0
    return width * height


def check_fits(needed: MemoryEstimate, memory: int | None = None) -> None:
    """Refuse a render that needs more than this machine's memory, naming the largest
    part and what to change."""
    memory = machine_memory() if memory is None else memory
    if memory is None or needed.total <= memory:
        return
    largest = max(needed.parts, key=needed.parts.get)
    listed = ", ".join(
        f"{part} {size / 2**30:.1f} GiB ({needed.counts[part]})"
        for part, size in sorted(needed.parts.items(), key=lambda item: -item[1])
        if size >= 2**28
    )
    raise SceneError(
        "scene",
        largest,
        f"the render needs about {needed.total / 2**30:.1f} GiB ({listed}), more than this "
        f"machine's {memory / 2**30:.1f} GiB of memory; {REMEDIES[largest]}",
    )
