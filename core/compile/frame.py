"""The frame: camera rays, lens, ambient and background, and the render options."""

from __future__ import annotations

import math

import numpy as np

from ..kernels.layout import Frame
from ..kernels.options import (
    HIDDEN_FROM_CAMERA,
    HIDDEN_FROM_DIFFUSE,
    HIDDEN_FROM_GLOSSY,
    HIDDEN_FROM_TRANSMISSION,
    OPTION_BUMP_TERMINATOR,
    OPTION_COUNT,
    OPTION_CRYPTO_LEVELS,
    OPTION_ENVIRONMENT,
    OPTION_ENVIRONMENT_CLOSEST,
    OPTION_ENVIRONMENT_HIDDEN,
    OPTION_ENVIRONMENT_SAMPLES,
    OPTION_GLASS_SHADOWS,
    OPTION_GLOSSY_SAMPLES,
    OPTION_MAX_DEPTH,
    OPTION_PASSES,
    OPTION_PIXEL_PATTERN,
    OPTION_PIXEL_SAMPLES,
    OPTION_PROJECTION,
    OPTION_ROUGH_DIFFUSE,
    OPTION_SEED,
    OPTION_SHADOW_ADAPTIVE,
    OPTION_SHADOW_CULLING,
    OPTION_SHADOW_PATTERN,
    OPTION_SHADOW_SAMPLES,
    OPTION_TRANSPARENT,
    PASSES_ANY,
    PASSES_LIGHT_SPLIT,
    PASSES_UV,
    PIXEL_PATTERNS,
    PROJECTION_ORTHOGRAPHIC,
    PROJECTIONS,
    SHADOW_PATTERNS,
)
from ..model import RenderSettings, Scene
from ..passes import MIST_FALLOFFS, layout
from ..vocabulary import BUMP_TERMINATORS, GLASS_SHADOWS, ROUGH_DIFFUSE_MODELS
from .environment import environment_kind

# Listing an area light's shapes costs about as much per shading point as tracing a few
# shadow rays: on the final scene (300 x 300) culling was slower at 1 to 6 rays per light
# (0.68 s against 0.53 s at 1), even at 8 and faster from 12 (0.99 s against 1.11 s), 1.4x at 40
SHADOW_CULLING_MIN_SAMPLES = 8


def _lens(camera) -> np.ndarray:
    """Aperture radius, focal distance, blades (0: a disk), rotation, 1 / ratio, clip start,
    clip end (inf: none)."""
    blades = camera.aperture_blades if camera.aperture_blades >= 3 else 0
    return np.array(
        [camera.aperture_radius, camera.focal_distance, blades, camera.aperture_rotation,
         1.0 / camera.aperture_ratio, camera.clip_start, camera.clip_end],
        float,
    )  # fmt: skip


def pack_frame(scene: Scene, settings: RenderSettings) -> Frame:
    return Frame(
        camera=_camera(scene, settings),
        lens=_lens(scene.camera),
        ambient=np.asarray(scene.ambient, float),
        background=np.asarray(scene.background, float),
        options=_options(scene, settings),
        pass_offset=layout(settings.passes, settings.crypto_levels)[0],
        mist=np.array(
            [
                settings.mist_start,
                1.0 / settings.mist_depth if settings.mist_depth > 0.0 else 0.0,
                MIST_FALLOFFS[settings.mist_falloff],
            ]
        ),
        sampling=np.array([settings.adaptive_threshold]),
    )


def _options(scene: Scene, settings: RenderSettings) -> np.ndarray:
    options = np.zeros(OPTION_COUNT, np.int64)
    options[OPTION_PROJECTION] = PROJECTIONS[scene.camera.projection]
    options[OPTION_MAX_DEPTH] = settings.max_depth
    options[OPTION_PIXEL_SAMPLES] = settings.pixel_samples
    options[OPTION_PIXEL_PATTERN] = PIXEL_PATTERNS[settings.pixel_sampling]
    options[OPTION_SHADOW_SAMPLES] = settings.shadow_samples
    options[OPTION_SHADOW_PATTERN] = SHADOW_PATTERNS[settings.shadow_sampling]
    options[OPTION_SHADOW_ADAPTIVE] = settings.adaptive_shadows
    options[OPTION_SEED] = settings.seed
    options[OPTION_TRANSPARENT] = settings.transparent
    options[OPTION_PASSES] = pass_bits(settings.passes)
    options[OPTION_CRYPTO_LEVELS] = settings.crypto_levels
    environment = scene.environment
    options[OPTION_ENVIRONMENT] = environment_kind(environment)
    options[OPTION_ENVIRONMENT_SAMPLES] = settings.environment_samples
    options[OPTION_GLOSSY_SAMPLES] = settings.glossy_samples
    options[OPTION_BUMP_TERMINATOR] = BUMP_TERMINATORS[settings.bump_terminator]
    options[OPTION_ROUGH_DIFFUSE] = ROUGH_DIFFUSE_MODELS[settings.rough_diffuse]
    options[OPTION_GLASS_SHADOWS] = GLASS_SHADOWS[settings.glass_shadows]
    options[OPTION_ENVIRONMENT_CLOSEST] = (
        environment is not None and environment.interpolation == "closest"
    )
    options[OPTION_ENVIRONMENT_HIDDEN] = hidden_bits(environment)
    options[OPTION_SHADOW_CULLING] = (
        settings.shadow_culling and settings.shadow_samples >= SHADOW_CULLING_MIN_SAMPLES
    )
    return options


def hidden_bits(environment) -> int:
    """OPTION_ENVIRONMENT_HIDDEN: the rays an environment is black to."""
    if environment is None:
        return 0
    switches = (
        (environment.camera, HIDDEN_FROM_CAMERA),
        (environment.diffuse, HIDDEN_FROM_DIFFUSE),
        (environment.glossy, HIDDEN_FROM_GLOSSY),
        (environment.transmission, HIDDEN_FROM_TRANSMISSION),
    )
    return sum(bit for visible, bit in switches if not visible)


def pass_bits(passes: tuple[str, ...]) -> int:
    """OPTION_PASSES: which costly parts of the passes the kernels must compute."""
    if not passes:
        return 0
    bits = PASSES_ANY
    if {"diffuse", "specular", "shadow"} & set(passes):
        bits |= PASSES_LIGHT_SPLIT
    if "uv" in passes:
        bits |= PASSES_UV
    return bits


def _camera(scene: Scene, settings: RenderSettings) -> np.ndarray:
    """Rows: the eye, the ray through the image centre, and the image plane's half extents
    along right and up (see `Frame.camera`, for either projection)."""
    cam = scene.camera
    forward = np.asarray(cam.view, float)
    forward /= np.linalg.norm(forward)
    right = np.cross(forward, np.asarray(cam.up, float))
    right /= np.linalg.norm(right)
    up = np.cross(right, forward)
    orthographic = PROJECTIONS[cam.projection] == PROJECTION_ORTHOGRAPHIC
    if orthographic:
        half_height, base = cam.ortho_height / 2.0, np.asarray(cam.eye, float)
    else:
        half_height, base = math.tan(math.radians(cam.fovy) / 2.0), forward
    half_width = half_height * settings.width / settings.height
    # The lens shift moves the image in its plane, in half-widths and half-heights:
    # perspective, the ray through its centre (still one unit along the view, so the plane in
    # focus stays perpendicular to the view); orthographic, the centre itself
    centre = base + right * half_width * cam.shift[0] + up * half_height * cam.shift[1]
    if orthographic:
        return np.array([centre, forward, right * half_width, up * half_height], float)
    return np.array([cam.eye, centre, right * half_width, up * half_height], float)
