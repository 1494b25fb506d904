"""Slots of `PackedScene.options`, the render settings the kernels read."""

OPTION_MAX_DEPTH = 0
OPTION_PIXEL_SAMPLES = 1
OPTION_PIXEL_JITTER = 2
OPTION_SHADOW_SAMPLES = 3
OPTION_SHADOW_STRATIFIED = 4
OPTION_SEED = 5
OPTION_LENS_STRIDE = 6  # shuffles lens cells against pixel cells (see render_tile)
OPTION_COUNT = 7
