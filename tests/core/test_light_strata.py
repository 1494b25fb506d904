"""Stratified shadow rays shared out among a pixel's camera rays (core.kernels.light_samples
`light_spread` and `square_point`): with n x n camera rays of s shadow rays each, each of the
light's s cells is cut n x n, and every part gets exactly one of the pixel's rays.

Checked against the exact answer, not against an earlier picture: the floor under the
`shadows` chart's rectangle light and box (tests/benchmarks/bench_sampling), whose irradiance
at a point is the light's integral of cos(theta) less the integral over the box's shadow
polygon on the light, by Gauss quadrature in numpy; a default-grid pixel's exact value is
the mean of that at its 3 x 3 camera points.
"""

import numpy as np
import pytest

from core import RenderSettings, render
from core.kernels.light_samples import (
    STRATA_KEY,
    STRATA_PLACE,
    STRATA_SIDE,
    light_spread,
    square_point,
    stratified_cell,
)
from core.kernels.options import SHADOW_STRATIFIED
from core.kernels.rng import permuted
from tests.benchmarks import bench_sampling as shadows

SEEDS = 8


@pytest.fixture(scope="module")
def penumbra():
    """(scene, pixels (rows, columns) of the penumbra, their exact values by camera rays per
    side: NaN where a camera ray sees the box, not the floor)."""
    scene = shadows.shadow_scene()
    # The penumbra's pixels, chosen by a render (at 64 shadow rays, between 3% and 97% of the
    # open floor's light); their exact values are the reference's
    light = render(scene, RenderSettings(shadows.SIZE, shadows.SIZE, pixel_samples=1,
                                         shadow_samples=64)).image[..., 0]  # fmt: skip
    open_floor = shadows.irradiance_reference(np.zeros(3))
    rows, columns = np.nonzero((light > 0.03 * open_floor) & (light < 0.97 * open_floor))
    assert len(rows) > 40
    exact = {side: shadows.floor_reference_at(side, rows, columns) for side in (2, 3)}
    return scene, (rows, columns), exact


def penumbra_errors(penumbra, sampling, shadow_samples=1, side=3):
    """Each seed's pixels that see only the floor minus their exact values, (SEEDS, pixels)."""
    scene, (rows, columns), exact = penumbra
    floor = np.isfinite(exact[side])
    errors = []
    for seed in range(SEEDS):
        settings = RenderSettings(
            shadows.SIZE, shadows.SIZE, pixel_samples=side, shadow_samples=shadow_samples,
            shadow_sampling=sampling, seed=seed,
        )  # fmt: skip
        image = render(scene, settings).image
        errors.append(image[rows[floor], columns[floor], 0] - exact[side][floor])
    return np.array(errors)


def test_a_pixels_rays_share_the_cells_so_its_penumbra_has_less_noise(penumbra):
    """At 3 x 3 camera rays and one shadow ray each, the pixel's nine shadow rays fall in
    nine different cells of the light: the penumbra's RMSE is well below that of nine
    independent points (uniform), and the estimate stays unbiased."""
    stratified = penumbra_errors(penumbra, "stratified")
    uniform = penumbra_errors(penumbra, "uniform")
    rmse_stratified = np.sqrt(np.mean(stratified**2))
    rmse_uniform = np.sqrt(np.mean(uniform**2))
    print(f"penumbra RMSE, stratified {rmse_stratified:.5f}, uniform {rmse_uniform:.5f}")
    assert rmse_stratified < 0.6 * rmse_uniform, (rmse_stratified, rmse_uniform)
    # Unbiased: the mean error over seeds and pixels is within four standard errors of 0
    standard_error = stratified.std() / np.sqrt(stratified.size)
    assert abs(stratified.mean()) < 4.0 * standard_error + 1e-4, (stratified.mean(), standard_error)


def test_one_shared_ray_a_camera_ray_beats_uniform_at_two_by_two(penumbra):
    """At 2 x 2 camera rays too (four places in a pixel's order, the smallest grid), by less
    (measured 0.85x uniform's error, against 0.48x at 3 x 3): four cells of a light cut a
    penumbra's edge less finely than nine, and a random order of four places is mostly a
    turn of the camera ray's own place (core.kernels.rng.permuted)."""
    stratified = np.sqrt(np.mean(penumbra_errors(penumbra, "stratified", side=2) ** 2))
    uniform = np.sqrt(np.mean(penumbra_errors(penumbra, "uniform", side=2) ** 2))
    print(f"penumbra RMSE at 2 x 2, stratified {stratified:.5f}, uniform {uniform:.5f}")
    assert stratified < 0.9 * uniform, (stratified, uniform)


@pytest.mark.parametrize("side", [2, 3, 4, 7])
def test_the_pixels_camera_rays_take_every_cell_of_the_light_once(side):
    """One shadow ray a camera ray: whatever the light and the bounce (the stream), the
    pixel's n x n camera rays take the n x n cells of the light once each."""
    strata = np.zeros(3, np.uint64)
    strata[STRATA_SIDE] = side
    count = side * side
    for pixel_key in (1, 12345, 2**63 + 7):
        strata[STRATA_KEY] = pixel_key
        for stream in (0, 1, 65536 * 3 + 2):
            taken = set()
            for k in range(count):
                strata[STRATA_PLACE] = permuted(k, count, np.uint64(pixel_key))
                spread = light_spread(strata, SHADOW_STRATIFIED, 1, stream)
                a, b = square_point(SHADOW_STRATIFIED, 1, 0, np.uint64(k), stream, (0.0, 0.0),
                                    spread)  # fmt: skip
                taken.add((int(b * side), int(a * side)))
            assert len(taken) == count, (pixel_key, stream)


@pytest.mark.parametrize("shadow_rays", [2, 4, 7, 40])
def test_more_rays_a_camera_ray_keep_their_own_cells(shadow_rays):
    """More than one shadow ray a camera ray: point j lies in cell j of the camera ray's own
    `shadow_rays` cells, anywhere in it, as without the sharing."""
    strata = np.zeros(3, np.uint64)
    strata[STRATA_SIDE], strata[STRATA_KEY], strata[STRATA_PLACE] = 3, 12345, 5
    spread = light_spread(strata, SHADOW_STRATIFIED, shadow_rays, 0)
    assert spread == (0, 0, 0)
    for k in range(20):
        for j in range(shadow_rays):
            a, b = square_point(SHADOW_STRATIFIED, shadow_rays, j, np.uint64(k), 0, (0.0, 0.0),
                                spread)  # fmt: skip
            x0, y0, w, h = stratified_cell(j, shadow_rays)
            assert x0 <= a < x0 + w and y0 <= b < y0 + h
