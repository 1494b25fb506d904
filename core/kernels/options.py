"""Slots of `PackedScene.options`, the render settings the kernels read."""

OPTION_MAX_DEPTH = 0
OPTION_PIXEL_SAMPLES = 1
OPTION_PIXEL_PATTERN = 2  # one of PIXEL_*
OPTION_SHADOW_SAMPLES = 3
OPTION_SHADOW_PATTERN = 4  # one of SHADOW_*
OPTION_SEED = 5
OPTION_SHADOW_CULLING = 6  # 1: area lights' shadow rays test only the shapes in their pyramid
OPTION_COUNT = 7

# Where a pixel's n x n camera rays pass: cell centres, a random point per cell, or n x n
# independent random points anywhere in the pixel
PIXEL_GRID, PIXEL_JITTERED, PIXEL_RANDOM = 0, 1, 2
PIXEL_PATTERNS = {"grid": PIXEL_GRID, "jittered": PIXEL_JITTERED, "random": PIXEL_RANDOM}
# Where an area light's N shadow rays end: independent random points, one per equal-area
# cell, or the first N points of the Halton sequence (bases 2, 3), randomly shifted
SHADOW_UNIFORM, SHADOW_STRATIFIED, SHADOW_HALTON = 0, 1, 2
SHADOW_PATTERNS = {"uniform": SHADOW_UNIFORM, "stratified": SHADOW_STRATIFIED,
                   "halton": SHADOW_HALTON}  # fmt: skip
