"""The tile driver: split the image into tiles, render them on worker threads, hand each back.

Threads rather than numba's `prange`: each worker calls the GIL-free tile kernel, so tiles run
truly in parallel, yet the calling thread gets every tile the moment it is done (Blender
streams it into the Image Editor), checks for cancellation between tiles, and never launches
two parallel numba regions at once (which the default threading layer does not survive).
Only as many tiles as there are threads are ever in flight, and a cancel (or Ctrl-C, or any
exception here) also sets a flag the tile kernel reads at every pixel: the tiles in flight
stop within a pixel's rays, not at their end.
"""

from __future__ import annotations

import contextlib
import os
import threading
import time
from collections.abc import Callable
from concurrent.futures import FIRST_COMPLETED, ThreadPoolExecutor, wait
from dataclasses import dataclass, field
from pathlib import Path

import numba
import numpy as np

from .compile import CompiledScene, compile_scene
from .compile.features import left_out, used_features
from .jit.cache_folder import load_or_rebuild, note_use
from .jit.variants import features_of, made_variants, variant
from .kernels.csg import CROSSING_CAPACITY, SPAN_CAPACITY
from .kernels.layout import PackedScene
from .kernels.render_tile import render_tile
from .kernels.shadow_log import SHADOW_LOG_SIZE, STATE_OVERFLOWED, VARYING_CAPACITY
from .kernels.workspace import (
    RAY_COUNT_SLOTS,
    RAYS_TRACED,
    SHADOW_RAYS,
    SHADOW_RAYS_UNOBSTRUCTED,
    new_workspace,
)
from .model import RenderSettings, Scene
from .passes import CRYPTO_PASSES, layout, split
from .threads import available_threads

# Set (=1): every scene renders with the full kernel, for comparison (core.jit.variants)
FULL_KERNEL_SWITCH = "WHITTED_FULL_KERNEL"
# How often the driver asks "cancelled?" while tiles are still running.
_CANCEL_POLL_S = 0.05
# The final render, the viewport and previews each render on threads of their own: the first
# to need the kernels loads (or compiles) them, the others wait for it, not compile them twice
_KERNELS_LOCK = threading.Lock()


@dataclass(frozen=True)
class Tile:
    """A rectangle of the image in pixels; y counts rows from the top of the image."""

    x: int
    y: int
    width: int
    height: int


@dataclass
class RenderStats:
    kernel_s: float  # time to get the kernels ready: compile, or load from the cache
    kernel_source: str  # "compiled", "cache" or "memory" (already loaded in this process)
    render_s: float  # wall time spent rendering tiles
    tiles_done: int
    tiles_total: int
    threads: int
    rays_traced: int = 0  # camera, reflected and refracted rays (each finds its closest hit)
    shadow_rays: int = 0  # rays towards lights (each asks only what light gets through)
    # of shadow_rays, those answered with no test: no shape met the area light's pyramid
    shadow_rays_unobstructed: int = 0
    # the compile's photon pass (core.compile.caustics): photons traced, stored, its seconds
    photons_traced: int = 0
    photons_stored: int = 0
    photon_s: float = 0.0
    photons_automatic: bool = False  # the count was the automatic budget's

    @property
    def rays_cast(self) -> int:
        return self.rays_traced + self.shadow_rays

    def summary(self) -> str:
        """The line the command line and Blender both print: "kernels cache 0.12 s | render
        1.52 s | 3.1 M rays (1.2 M shadow), 2.04 M rays/s | 4 threads"."""
        rate = self.rays_cast / self.render_s / 1e6 if self.render_s > 0 else 0.0
        # a photon may be stored at more than one surface: "traced, stored", not "of"
        caustics = (
            f"caustics {self.photon_s:.2f} s, {self.photons_traced:,} photons traced"
            f"{' (automatic)' if self.photons_automatic else ''}, "
            f"{self.photons_stored:,} stored | "
            if self.photons_traced
            else ""
        )
        return (
            f"kernels {self.kernel_source} {self.kernel_s:.2f} s | {caustics}"
            f"render {self.render_s:.2f} s"
            f" | {_millions(self.rays_cast)} M rays ({_millions(self.shadow_rays)} M shadow), "
            f"{rate:.2f} M rays/s | {self.threads} threads"
        )


def _millions(count: int) -> str:
    """A count in millions, with the digits a small render needs (the farm adds its tasks'
    counts: 0.0 each would sum to nothing)."""
    return f"{count / 1e6:.1f}" if count >= 1e6 else f"{count / 1e6:.3f}"


@dataclass
class RenderOutput:
    image: np.ndarray  # float32 (height, width, 4) linear RGBA, row 0 at the top
    stats: RenderStats
    cancelled: bool
    warnings: list[str]  # things the scene asked for that were left out (each once)
    # the passes asked for (RenderSettings.passes), name -> float32 (height, width, channels)
    passes: dict[str, np.ndarray] = field(default_factory=dict)


# on_tile(tile, pixels, done, total): pixels float32 (tile.height, tile.width, 4 + channels),
# RGBA then the passes as core.passes.layout places them (`core.passes.split` names them)
TileCallback = Callable[[Tile, np.ndarray, int, int], None]


def split_into_tiles(region: tuple[int, int, int, int], tile_size: int) -> list[Tile]:
    """Tiles covering `region` (x, y, width, height) exactly once, row by row from the top."""
    x0, y0, width, height = region
    return [
        Tile(x, y, min(tile_size, x0 + width - x), min(tile_size, y0 + height - y))
        for y in range(y0, y0 + height, tile_size)
        for x in range(x0, x0 + width, tile_size)
    ]


def tile_kernel(packed: PackedScene):
    """The tile kernel that renders `packed`: a variant compiled without features it does not
    use (core.kernels.features), which compiles in about half the time and renders faster.
    Of the kernels compiled already (in this process or the cache) that hold every feature
    it uses, the one with the fewest; the full kernel holds them all (the warm-up's, or the
    extension's). None compiled: its own variant, which the first call compiles."""
    if full_kernel_asked():
        return render_tile
    leave_out = left_out(packed)
    own = variant(render_tile, leave_out)
    if own.signatures:
        return own
    # Loaded in this process first: a viewport renders many times, and reads no file again
    loaded = _fewest_features(leave_out, [(w, k) for w, k in _made_here() if k.signatures])
    if loaded is not None:
        return loaded
    if _in_cache(own):
        return own
    cached = [(w, k) for w, k in compiled_variants() if _in_cache(k)]
    return _fewest_features(leave_out, cached) or own


def _fewest_features(leave_out: frozenset[str], kernels):
    """Of (left out, kernel) pairs, the kernel holding every feature but `leave_out` that
    leaves out the most, or None."""
    fitting = [(len(without), kernel) for without, kernel in kernels if without <= leave_out]
    return max(fitting, key=lambda entry: entry[0])[1] if fitting else None


def _made_here():
    """(left out, kernel) of the full kernel and the variants made in this process."""
    return [(frozenset(), render_tile), *made_variants(render_tile)]


def full_kernel_asked() -> bool:
    """Whether WHITTED_FULL_KERNEL=1 asks every render to take the full kernel."""
    return os.environ.get(FULL_KERNEL_SWITCH, "") not in ("", "0")


def compiled_variants():
    """(left out, kernel) of every tile kernel that may be compiled: the full kernel, those
    made in this process, and those whose cache index files lie in the kernel cache."""
    found = dict(_made_here())
    folder = _cache_folder(render_tile)
    if folder is not None:
        for index in folder.glob(f"*.{render_tile.__name__}__without_*.nbi"):
            bits = index.name.split("__without_")[1].split("-")[0]
            with contextlib.suppress(ValueError):
                without = features_of(bits)
                found.setdefault(without, variant(render_tile, without))
    return list(found.items())


def _cache_folder(kernel) -> Path | None:
    try:
        return Path(kernel._cache._cache_path)
    except Exception:  # numba's private cache object, read with care
        return None


def kernel_compile_note(packed: PackedScene) -> str:
    """What a render of `packed` will compile first, "" when its kernel is ready (in this
    process or the cache): "compiling the kernel for this scene (first use: ...)"."""
    if numba.config.DISABLE_JIT:
        return ""
    kernel = tile_kernel(packed)
    if kernel.signatures or _in_cache(kernel):
        return ""
    features = ", ".join(sorted(used_features(packed))) or "none beyond the basics"
    return (
        f"compiling the render kernel for this scene's features ({features}); first use "
        "on this machine, not render time"
    )


def _in_cache(kernel) -> bool:
    """Whether numba's cache holds machine code of `kernel` for this source (its index file
    lists an overload): a call then loads it rather than compiles. numba's private index,
    read with care: any surprise says no, and the call compiles as it would."""
    try:
        return bool(kernel._cache._cache_file._load_index())
    except Exception:
        return False


def prepare_kernels(packed: PackedScene) -> tuple[float, str]:
    """Compile the kernels for `packed` (`tile_kernel`), or load them from the cache.

    Returns (seconds, source). Done once on the calling thread so that worker threads never
    compile concurrently and so that compile time is reported apart from render time.
    """
    seconds, source, _ = _ready_kernel(packed)
    return seconds, source


def _ready_kernel(packed: PackedScene):
    """(seconds, source, the tile kernel) of `prepare_kernels`."""
    if numba.config.DISABLE_JIT:  # NUMBA_DISABLE_JIT=1: the kernels run as Python
        return 0.0, "python", render_tile
    with _KERNELS_LOCK:
        kernel = tile_kernel(packed)
        return (*_prepare_kernels(packed, kernel), kernel)


def prepare_kernel(packed: PackedScene, kernel) -> tuple[float, str]:
    """`prepare_kernels` with a given tile kernel (a variant: the warm-up's)."""
    with _KERNELS_LOCK:
        return _prepare_kernels(packed, kernel)


def _prepare_kernels(packed: PackedScene, kernel) -> tuple[float, str]:
    already = bool(kernel.signatures)
    hits_before = sum(kernel.stats.cache_hits.values())
    start = time.perf_counter()
    empty = np.empty((0, 0, 4), np.float32)
    _, rebuilt = load_or_rebuild(lambda: kernel(packed, 1, 1, 0, 0, 0, 0, empty, new_workspace(0)))
    seconds = time.perf_counter() - start
    if already:
        return seconds, "memory"
    note_use()  # once a process: what keeps this cache folder from being pruned
    loaded = sum(kernel.stats.cache_hits.values()) > hits_before
    return seconds, "cache" if loaded and not rebuilt else "compiled"


def preload_kernels() -> tuple[float, str]:
    """Load the kernels into this process before any render needs them, as `prepare_kernels`
    does for the first render. Blender's window does it on a thread of its own once the
    kernel warm-up is done, so that the first Rendered viewport shows in a tenth of a second
    rather than after the third of a second loading takes."""
    return prepare_kernels(compile_scene(Scene(), RenderSettings(width=1, height=1)).packed)


def render(
    scene: Scene,
    settings: RenderSettings,
    on_tile: TileCallback | None = None,
    should_cancel: Callable[[], bool] | None = None,
    on_photons: Callable[[int, int], None] | None = None,
) -> RenderOutput:
    """Render `scene`. Raises `SceneError` for bad input before any work starts.

    on_tile(tile, pixels, tiles_done, tiles_total) is called on this thread after each tile,
    with pixels float32 (tile.height, tile.width, 4 + pass channels), row 0 at the top.
    should_cancel() is polled between tiles; once it says True no new tile starts and render
    returns with `cancelled` set and the unrendered pixels zero.
    on_photons(done, total) is called as the caustic photon pass goes (when it runs), which
    should_cancel() also stops.
    """
    compiled = compile_scene(scene, settings, on_photons, should_cancel)
    return render_compiled(compiled, settings, on_tile, should_cancel)


def render_compiled(
    compiled: CompiledScene,
    settings: RenderSettings,
    on_tile: TileCallback | None = None,
    should_cancel: Callable[[], bool] | None = None,
) -> RenderOutput:
    """`render` of a scene compiled already (`compile_scene`, `compile.with_frame`) for
    `settings`: the viewport compiles once and renders it at several sizes."""
    kernel_s, kernel_source, kernel = _ready_kernel(compiled.packed)
    threads = settings.threads or available_threads()
    tiles = split_into_tiles(settings.pixel_region(), settings.tile_size)
    _, pass_channels = layout(settings.passes, settings.crypto_levels)
    pixels_all = np.zeros((settings.height, settings.width, 4 + pass_channels), np.float32)
    tally = _Tally()

    def finished(tile: Tile, result: tuple) -> None:
        pixels = tally.add(result)
        pixels_all[tile.y : tile.y + tile.height, tile.x : tile.x + tile.width] = pixels
        if on_tile is not None:
            on_tile(tile, pixels, tally.tiles_done, len(tiles))

    start = time.perf_counter()
    cancelled = _run_tiles(compiled.packed, kernel, settings, tiles, threads, finished,
                           should_cancel)  # fmt: skip
    stats = RenderStats(
        kernel_s=kernel_s,
        kernel_source=kernel_source,
        render_s=time.perf_counter() - start,
        tiles_done=tally.tiles_done,
        tiles_total=len(tiles),
        threads=threads,
        rays_traced=int(tally.ray_counts[RAYS_TRACED]),
        shadow_rays=int(tally.ray_counts[SHADOW_RAYS]),
        shadow_rays_unobstructed=int(tally.ray_counts[SHADOW_RAYS_UNOBSTRUCTED]),
    )
    if compiled.caustics is not None:
        stats.photons_traced = compiled.caustics.traced
        stats.photons_stored = compiled.caustics.stored
        stats.photon_s = compiled.caustics.seconds
        stats.photons_automatic = compiled.caustics.budget is not None
    warnings = list(compiled.warnings)
    if tally.csg_overflows:
        warnings.append(
            f"{tally.csg_overflows} rays met more CSG surfaces than one ray can hold "
            f"({SPAN_CAPACITY} spans, {CROSSING_CAPACITY} crossings of one mesh operand): "
            "the excess were dropped, and those pixels may be wrong"
        )
    if tally.shadow_overflows:
        warnings.append(
            f"{tally.shadow_overflows} shadow rays crossed more surfaces whose transparency "
            f"varies than a shading point can hold ({VARYING_CAPACITY} crossings, "
            f"{SHADOW_LOG_SIZE} shadow rays): they were taken as blocked, and those pixels "
            "may be too dark"
        )
    # Copies, not views: a caller that keeps only the image does not keep every pass with it
    image = pixels_all[..., :4].copy() if pass_channels else pixels_all
    passes = {
        name: np.ascontiguousarray(values)
        for name, values in split(pixels_all, settings.passes, settings.crypto_levels).items()
    }
    return RenderOutput(image, stats, cancelled, warnings, passes)


class _Tally:
    """What the finished tiles add up to: how many, their rays, their CSG overflows and
    shadow rays taken as blocked for lack of room (core.kernels.shadow_log)."""

    def __init__(self):
        self.tiles_done = 0
        self.csg_overflows = 0
        self.shadow_overflows = 0
        self.ray_counts = np.zeros(RAY_COUNT_SLOTS, np.int64)

    def add(self, result: tuple) -> np.ndarray:
        pixels, overflows, shadow_overflows, counts = result
        self.tiles_done += 1
        self.csg_overflows += overflows
        self.shadow_overflows += shadow_overflows
        self.ray_counts += counts
        return pixels


def _render_one(packed: PackedScene, kernel, settings: RenderSettings, tile: Tile, stop):
    """One tile on a worker thread: (pixels, rays whose CSG spans overflowed, shadow rays
    whose varying crossings did not fit, ray counts)."""
    _, pass_channels = layout(settings.passes, settings.crypto_levels)
    pixels = np.empty((tile.height, tile.width, 4 + pass_channels), np.float32)
    # Cryptomatte keeps each camera ray's ids until its pixel is done; a pixel of adaptive
    # anti-aliasing whose samples agree counts its corners once and its centre four times
    crypto = any(name in CRYPTO_PASSES for name in settings.passes)
    adaptive = settings.adaptive_threshold > 0
    crypto_rays = max(settings.pixel_samples**2, 8 if adaptive else 1) if crypto else 1
    workspace = new_workspace(
        settings.max_depth, max(settings.shadow_samples, settings.environment_samples), stop,
        crypto_rays, settings.glossy_samples, tile.width + 1 if adaptive else 1,
    )  # fmt: skip
    kernel(packed, settings.width, settings.height, tile.x, tile.y, tile.width, tile.height,
           pixels, workspace)  # fmt: skip
    stacks = workspace.stacks
    shadow_overflows = int(stacks.shadow_state[STATE_OVERFLOWED])
    return pixels, int(stacks.csg.overflow[0]), shadow_overflows, stacks.ray_counts


def _run_tiles(packed, kernel, settings, tiles, threads, finished, should_cancel) -> bool:
    """Render `tiles` on `threads` workers, calling finished(tile, result) on this thread as
    each completes, at most `threads` in flight; True if should_cancel() stopped it."""
    stop = np.zeros(1, np.int64)  # the kernels' cancel flag (Workspace.cancel)
    cancelled = False
    with ThreadPoolExecutor(max_workers=threads, thread_name_prefix="whitted") as pool:
        queue = iter(tiles)
        running = {}

        def start_next() -> None:
            tile = next(queue, None)
            if tile is not None:
                running[pool.submit(_render_one, packed, kernel, settings, tile, stop)] = tile

        try:
            for _ in range(threads):
                start_next()
            while running and not cancelled:
                done, _ = wait(running, timeout=_CANCEL_POLL_S, return_when=FIRST_COMPLETED)
                for future in done:
                    finished(running.pop(future), future.result())
                cancelled = should_cancel is not None and should_cancel()
                if not cancelled:
                    for _ in done:
                        start_next()
        finally:
            # Tiles still in flight stop at their next pixel (their pixels are dropped), so
            # leaving the pool, which waits for them, takes no longer than that
            stop[0] = 1
    return cancelled
