"""The tile driver: exact coverage, the same pixels for any tiling, prompt cancel."""

import threading
import time

import numba
import numpy as np
import pytest

from core import RenderSettings, render, split_into_tiles
from tests.support.scenes import ball_on_ground


@pytest.mark.parametrize(
    "region, tile", [((0, 0, 97, 41), 16), ((5, 3, 30, 70), 7), ((0, 0, 1, 1), 32)]
)
def test_tiles_cover_the_region_exactly_once(region, tile):
    x0, y0, w, h = region
    counts = np.zeros((y0 + h, x0 + w), int)
    for t in split_into_tiles(region, tile):
        assert 1 <= t.width <= tile and 1 <= t.height <= tile
        counts[t.y : t.y + t.height, t.x : t.x + t.width] += 1
    assert np.all(counts[y0:, x0:] == 1) and counts.sum() == w * h


def test_same_pixels_for_any_tile_size_and_thread_count():
    scene = ball_on_ground()
    reference = render(scene, RenderSettings(70, 50, tile_size=64, threads=1)).image
    for tile, threads in ((1, 2), (7, 2), (13, 1), (32, 3)):
        image = render(scene, RenderSettings(70, 50, tile_size=tile, threads=threads)).image
        np.testing.assert_array_equal(image, reference)


def test_region_render_matches_the_full_frame():
    scene = ball_on_ground()
    full = render(scene, RenderSettings(70, 50)).image
    part = render(scene, RenderSettings(70, 50, tile_size=8, region=(11, 9, 30, 25))).image
    np.testing.assert_array_equal(part[9:34, 11:41], full[9:34, 11:41])
    assert not part[:9].any() and not part[34:].any()


def test_every_tile_is_handed_back_on_the_calling_thread():
    scene = ball_on_ground()
    calls = []

    def on_tile(tile, pixels, done, total):
        calls.append((tile, pixels.copy(), done, total, threading.current_thread()))

    out = render(scene, RenderSettings(50, 30, tile_size=16), on_tile=on_tile)
    assert [c[2] for c in calls] == list(range(1, len(calls) + 1))
    assert all(c[3] == len(calls) == out.stats.tiles_total for c in calls)
    assert all(c[4] is threading.current_thread() for c in calls)
    for tile, pixels, *_ in calls:
        region = out.image[tile.y : tile.y + tile.height, tile.x : tile.x + tile.width]
        np.testing.assert_array_equal(pixels, region)


@pytest.mark.parametrize("threads", [1, 2])
def test_cancel_stops_within_one_tile_per_thread(threads):
    scene = ball_on_ground()
    tiles_seen = []
    out = render(
        scene,
        RenderSettings(64, 64, tile_size=8, threads=threads),
        on_tile=lambda tile, *_: tiles_seen.append(tile),
        should_cancel=lambda: len(tiles_seen) >= 1,
    )
    assert out.cancelled
    # The tile that triggered the cancel, plus at most the others already running
    assert 1 <= out.stats.tiles_done <= threads
    assert out.stats.tiles_total == 64


@pytest.mark.skipif(numba.config.DISABLE_JIT, reason="nothing is compiled without the JIT")
def test_kernel_compile_time_is_reported_apart_from_render_time():
    out = render(ball_on_ground(), RenderSettings(8, 8))
    assert out.stats.kernel_source in {"compiled", "cache", "memory"}
    assert out.stats.kernel_s >= 0 and out.stats.render_s > 0


def test_cancel_stops_a_tile_in_flight_at_its_next_pixel():
    """One tile of a million pixels at 64 rays each takes some 12 s to finish here (Blender's
    Esc used to wait for such a tile: 13.9 s); the kernel reads the cancel flag at every
    pixel, so render returns as soon as the driver has seen the cancel."""
    asked = []

    def should_cancel():
        asked.append(time.perf_counter())
        return asked[-1] - asked[0] > 0.3

    settings = RenderSettings(1024, 1024, tile_size=1024, threads=1, pixel_samples=8)
    out = render(ball_on_ground(), settings, should_cancel=should_cancel)
    stopped = time.perf_counter() - asked[-1]
    assert out.cancelled and out.stats.tiles_done == 0
    assert not out.image.any()  # the tile's part-filled pixels are not handed back
    assert stopped < 1.0, stopped


def test_the_tile_kernel_returns_at_once_when_the_flag_is_set():
    from core.compile import compile_scene
    from core.kernels.render_tile import render_tile
    from core.kernels.workspace import new_workspace

    settings = RenderSettings(16, 16)
    packed = compile_scene(ball_on_ground(), settings).packed
    out = np.full((16, 16, 4), -7.0, np.float32)
    render_tile(packed, 16, 16, 0, 0, 16, 16, out, new_workspace(4, 1, np.ones(1, np.int64)))
    assert np.all(out == -7.0)
    render_tile(packed, 16, 16, 0, 0, 16, 16, out, new_workspace(4, 1))
    assert np.all(out[..., 3] == 1.0)


@pytest.mark.skipif(numba.config.DISABLE_JIT, reason="no kernels to load as Python")
def test_preloaded_kernels_serve_the_next_render_from_memory():
    from core.driver import preload_kernels

    _, source = preload_kernels()
    assert source in ("compiled", "cache", "memory")
    output = render(ball_on_ground(), RenderSettings(width=8, height=6))
    assert output.stats.kernel_source == "memory"
