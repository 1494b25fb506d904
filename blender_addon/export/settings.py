"""Render settings: output size, border, threads, and the Whitted render panel."""

from __future__ import annotations

import numpy as np

from .. import core
from ..compat import BUMP_TERMINATOR, ROUGH_DIFFUSE


def convert(scene) -> core.RenderSettings:
    render = scene.render
    scale = render.resolution_percentage / 100.0
    width = int(render.resolution_x * scale)
    height = int(render.resolution_y * scale)
    for field, value in (("resolution_x", width), ("resolution_y", height)):
        if value < 1:
            raise core.SceneError(
                f"scene '{scene.name}'",
                f"render {field}",
                f"{value} pixels after the {render.resolution_percentage}% scale; "
                "set Output Properties > Format > Resolution to at least 1",
            )
    threads = render.threads if render.threads_mode == "FIXED" else 0
    settings = scene.whitted
    return core.RenderSettings(
        width=width,
        height=height,
        tile_size=settings.tile_size,
        threads=threads,
        region=_border_region(render, width, height),
        max_depth=settings.max_depth,
        pixel_samples=settings.pixel_samples,
        pixel_sampling=settings.pixel_sampling.lower(),
        shadow_samples=settings.shadow_samples,
        shadow_sampling=settings.shadow_sampling.lower(),
        adaptive_shadows=settings.adaptive_shadows,
        adaptive_threshold=settings.adaptive_threshold if settings.use_adaptive_pixels else 0.0,
        environment_samples=settings.environment_samples,
        glossy_samples=settings.glossy_samples,
        bump_terminator=BUMP_TERMINATOR,
        rough_diffuse=ROUGH_DIFFUSE,
        seed=settings.seed,
        glass_shadows=settings.glass_shadows.lower(),
        caustics=_caustics(settings),
        caustic_photons="auto" if settings.use_auto_photons else settings.caustic_photons,
        transparent=render.film_transparent,
    )


def _caustics(settings) -> tuple[str, ...]:
    """The Render panel's caustic switches as core's names."""
    kinds = (("reflective", settings.use_caustics_reflective),
             ("refractive", settings.use_caustics_refractive))  # fmt: skip
    return tuple(name for name, on in kinds if on)


def _border_region(render, width, height):
    """The render border as core's region (y from the top), in whole pixels as Blender counts
    them: float32 border fraction times size, truncated."""
    if not render.use_border:
        return None

    def pixel(fraction, size):
        return int(np.float32(fraction) * np.float32(size))

    x_min, x_max = pixel(render.border_min_x, width), pixel(render.border_max_x, width)
    y_min, y_max = pixel(render.border_min_y, height), pixel(render.border_max_y, height)
    if x_max <= x_min or y_max <= y_min:
        return None  # Blender renders the whole frame for an empty border
    return (x_min, height - y_max, x_max - x_min, y_max - y_min)
