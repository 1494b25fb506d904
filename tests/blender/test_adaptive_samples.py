"""Adaptive anti-aliasing and adaptive soft shadows on every sample scene, against the fixed
grid's converged picture: each scene of each sample file, exported as a render sees it
(point lights made small area lights, so that every scene has penumbrae to refine).

Each adaptive mode competes with the fixed grid it adapts: adaptive anti-aliasing with n x n
camera rays against the fixed n' x n' grids, adaptive soft shadows against fixed shadow-ray
counts, the rest of the settings alike, and the converged picture is converged in that
dimension (8 x 8 camera rays, or 256 shadow rays, the rest alike), so that the error
measured is the mode's own. At equal cost the adaptive render must be at least as
close to the converged picture as every such fixed grid that casts no more rays (rays cast
stand for time: a test does not time), and it must stitch: any tiling gives the same bits.

(Across modes the fixed grids' own front decides: at this small size edges dominate, and
4 x 4 camera rays with 4 shadow rays beat 3 x 3 with 36 on most scenes, adaptive or not;
`bench_equal_error` charts the whole front on the final scene.)"""

import dataclasses
import sys

import numpy as np
import pytest

import core
from tests.blender.conftest import ROOT
from tests.support.render_view import export_scenes

pytestmark = pytest.mark.bpy
SAMPLES = sorted((ROOT / "sample_blends").glob("*.blend"))
WIDTH = 48
# Each mode: the adaptive settings, the fixed grids it competes with, the settings all share
MODES = {
    "anti-aliasing": (
        {"pixel_samples": 4, "adaptive_threshold": 0.02},
        [{"pixel_samples": n} for n in (1, 2, 3, 4)],
        {"shadow_samples": 9},
        {"pixel_samples": 8},
    ),
    "soft shadows": (
        {"shadow_samples": 64, "adaptive_shadows": True},
        [{"shadow_samples": s} for s in (4, 9, 16, 25, 36, 64)],
        {"pixel_samples": 2},
        {"shadow_samples": 256},
    ),
}


def as_area_light(light):
    """A point light as a square area light of side 0.3 around it, facing down."""
    if not isinstance(light, core.PointLight):
        return light
    return core.AreaLight(light.position, (0.3, 0.0, 0.0), (0.0, 0.3, 0.0), light.intensity,
                          light.attenuation, name=light.name)  # fmt: skip


def small(settings, **changes):
    """The scene's settings at WIDTH pixels, fixed grids unless `changes` say otherwise."""
    height = max(1, WIDTH * settings.height // settings.width)
    fixed = {"adaptive_threshold": 0.0, "adaptive_shadows": False}
    return dataclasses.replace(settings, width=WIDTH, height=height, region=None, threads=2,
                               **{**fixed, **changes})  # fmt: skip


def error(image, reference) -> float:
    """RMSE in linear RGB, clipped to what a picture file keeps."""
    difference = np.clip(image[..., :3], 0, 1) - np.clip(reference[..., :3], 0, 1)
    return float(np.sqrt(np.mean(difference**2)))


# Where adaptive anti-aliasing loses today (issue 42, open), measured at 48 pixels. Its
# samples disagree in nearly every pixel (92-97% refined), so it costs the fixed 4 x 4 grid
# and its five first samples too, and the fixed 4 x 4 grid is affordable: under depth of
# field each of the five has one lens sample, and their differences are the lens's noise;
# in the mirror a far checker, finer than a pixel, aliases, and the pixels it leaves
# unrefined are wrong (0.046 against the 4 x 4 grid's 0.040; the 3 x 3 grid's is 0.060).
# With the corners alone (before the centre sample) refraction and the final scene lost
# too (by 1.6x and 1.03x); now they win (0.74x, 0.91x). Strict: when one starts to pass,
# say so.
AA_LOSES = {"depth_of_field", "mirror"}


def cases():
    for path in SAMPLES:
        for mode in MODES:
            marks = []
            if mode == "anti-aliasing" and path.stem in AA_LOSES:
                reason = "adaptive anti-aliasing refines nearly every pixel here, and loses to "
                reason += "the fixed 4 x 4 grid (issue 42)"
                marks = [pytest.mark.xfail(strict=True, reason=reason)]
            yield pytest.param(path, mode, marks=marks, id=f"{path.stem}-{mode}")


@pytest.mark.parametrize(("path", "mode"), cases())
def test_adaptive_sampling_beats_the_fixed_grid_at_equal_cost_and_stitches(
    bpy_with_whitted, path, mode
):
    bpy = bpy_with_whitted
    bpy.ops.wm.open_mainfile(filepath=str(path))
    adaptive_settings, fixed_grids, shared, converged_settings = MODES[mode]
    for name, scene, settings in export_scenes(bpy, sys.modules["whitted.export"]):
        scene.lights = [as_area_light(light) for light in scene.lights]
        where = f"{path.name}, scene '{name}', adaptive {mode}"
        converged = core.render(scene, small(settings, **{**shared, **converged_settings})).image
        adaptive = core.render(scene, small(settings, **shared, **adaptive_settings))
        adaptive_error = error(adaptive.image, converged)
        affordable = []
        for grid in fixed_grids:
            fixed = core.render(scene, small(settings, **shared, **grid))
            if fixed.stats.rays_cast <= adaptive.stats.rays_cast:
                affordable.append((error(fixed.image, converged), str(grid)))
        assert affordable, f"{where}: no fixed grid casts as few rays"
        best = min(affordable)
        # A tie within rounding is no loss: where nothing needs refining both draw alike
        assert adaptive_error <= best[0] + 1e-6, (
            f"{where}: {adaptive_error:.5f} ({adaptive.stats.rays_cast} rays) against the fixed "
            f"{best[1]}: {best[0]:.5f}"
        )
        tiled = core.render(scene, small(settings, **shared, **adaptive_settings, tile_size=7))
        assert np.array_equal(tiled.image, adaptive.image), f"{where}: a tile seam"
