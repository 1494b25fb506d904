"""The viewport's newest image as a GPU texture, drawn over the 3D view with the `gpu` module
(`bgl` is gone in Blender 5.0). The texture is uploaded once per new image and drawn on every
redraw; the pixels stay scene-linear and premultiplied, and Blender's view transform applies
as it does to the final render (the engine's display-space shader is bound around the draw).
"""

from __future__ import annotations

import time

import numpy as np


class ViewTexture:
    def __init__(self):
        self.image = None  # the core.progressive.ViewImage uploaded
        self._texture = None
        self.drawn_at = 0.0  # perf_counter of the last upload

    def draw(self, engine, scene, image, view) -> None:
        """Draw `image` (None: nothing yet) stretched over the region, uploading it first if
        it is new. A coarse image of an older view stands in until the new one comes."""
        if image is None:
            return
        import gpu  # only in a window: Blender's background mode has no gpu module to draw
        from gpu_extras.presets import draw_texture_2d

        if image is not self.image or self._texture is None:
            self._texture = _upload(gpu, image.pixels)
            self.image, self.drawn_at = image, time.perf_counter()
        gpu.state.blend_set("ALPHA_PREMULT")
        engine.bind_display_space_shader(scene)
        draw_texture_2d(self._texture, (0, 0), view.width, view.height)
        engine.unbind_display_space_shader()
        gpu.state.blend_set("NONE")

    def free(self) -> None:
        self._texture = None
        self.image = None


def _upload(gpu, pixels: np.ndarray):
    """float32 (height, width, 4), row 0 at the top -> an RGBA16F texture, row 0 at the bottom
    as OpenGL counts."""
    height, width = pixels.shape[:2]
    flipped = np.ascontiguousarray(pixels[::-1], np.float32).reshape(-1)
    data = gpu.types.Buffer("FLOAT", flipped.size, flipped)
    return gpu.types.GPUTexture((width, height), format="RGBA16F", data=data)
