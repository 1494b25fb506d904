"""Slots of `PackedScene.options`, the render settings the kernels read."""

OPTION_MAX_DEPTH = 0
OPTION_PIXEL_SAMPLES = 1
OPTION_PIXEL_PATTERN = 2  # one of PIXEL_*
OPTION_SHADOW_SAMPLES = 3
OPTION_SHADOW_PATTERN = 4  # one of SHADOW_*
OPTION_SEED = 5
OPTION_SHADOW_CULLING = 6  # 1: area lights' shadow rays test only the shapes in their pyramid
OPTION_PROJECTION = 7  # one of PROJECTION_*
# 1: a camera ray that meets nothing is transparent (alpha 0, no background colour; Blender's
# Film > Transparent); reflected and refracted rays still see the background, as in Cycles
OPTION_TRANSPARENT = 8
# PASSES_* bits: passes beside Combined are asked for (Frame.pass_offset says which), and
# whether they need the lighting split or texture coordinates, which cost the most
OPTION_PASSES = 9
OPTION_CRYPTO_LEVELS = 10  # Cryptomatte ranks kept per pixel
OPTION_ENVIRONMENT = 11  # one of ENVIRONMENT_* (core.kernels.layout)
OPTION_ENVIRONMENT_SAMPLES = 12  # shadow rays towards the environment per shading point
OPTION_ENVIRONMENT_CLOSEST = 13  # 1: the image's nearest pixel, not bilinear
OPTION_ENVIRONMENT_HIDDEN = 14  # HIDDEN_FROM_* bits: rays the environment is black to
# rays spread over a rough mirror's or glass's lobe at a camera ray's hit (one at later
# hits); 0 keeps rough surfaces sharp (core.kernels.glossy)
OPTION_GLOSSY_SAMPLES = 15
# 1: adaptive soft shadows, an area light's probes deciding whether its samples' rays are
# cast (core.kernels.shadow_rays)
OPTION_SHADOW_ADAPTIVE = 16
# one of GLASS_SHADOWS_* (core.vocabulary): whether a shadow ray passes a refracting surface
OPTION_GLASS_SHADOWS = 17
# the shadow terminator term of a diffuse lit through a bent normal (Bump, Normal Map): one of
# TERMINATOR_* (core.vocabulary; core.kernels.bent_normal.terminator_term)
OPTION_BUMP_TERMINATOR = 18
OPTION_ROUGH_DIFFUSE = 19  # core.kernels.rough_diffuse's ROUGH_EON or ROUGH_FON
OPTION_COUNT = 20

# OPTION_ENVIRONMENT_HIDDEN's bits (Blender's World > Settings > Ray Visibility, off)
HIDDEN_FROM_CAMERA = 1
HIDDEN_FROM_DIFFUSE = 2
HIDDEN_FROM_GLOSSY = 4
HIDDEN_FROM_TRANSMISSION = 8

PASSES_ANY = 1
PASSES_LIGHT_SPLIT = 2  # the diffuse, specular and shadow passes
PASSES_UV = 4

# The patterns', projections' and emitters' codes, listed with their names in core.vocabulary
from ..vocabulary import (  # noqa: E402, F401
    EMITTER_ELLIPSE,
    EMITTER_FACING_DISK,
    EMITTER_MESH,
    EMITTER_RECTANGLE,
    EMITTER_SPHERE,
    EMITTER_SUN_CONE,
    EMITTER_SUN_DISK,
    PIXEL_GRID,
    PIXEL_JITTERED,
    PIXEL_PATTERNS,
    PIXEL_RANDOM,
    PROJECTION_ORTHOGRAPHIC,
    PROJECTION_PERSPECTIVE,
    PROJECTIONS,
    SHADOW_HALTON,
    SHADOW_PATTERNS,
    SHADOW_STRATIFIED,
    SHADOW_UNIFORM,
)
