"""The final render (F12, `blender -b`): export, wait for the kernels, render in tiles,
stream each tile back, report progress and the summary.

It only coordinates; the work is in `export` (Blender -> core.Scene) and in `core`.
"""

import time

import numpy as np

from .. import core, export
from ..core.jit.warmup_process import shared_warmup
from ..reporting import report_internal_failure
from . import kernel_status, result_notes

# Meshes converted by earlier final renders of this Blender session, so that the frames of an
# animation re-export only the meshes that changed. Kept here, not on the engine: Blender
# makes a new RenderEngine for each render, which would keep them for one frame only
MESHES = export.MeshCache()
# Material and world previews render Blender's preview scenes: their meshes are cached apart,
# or each thumbnail would evict the user's scene from MESHES
PREVIEW_MESHES = export.MeshCache()


def render(engine, depsgraph):
    """Render the depsgraph's frame into `engine`'s result. Esc (`cancelled`) is polled by
    the driver between tiles and while the kernels warm up. A preview (`is_preview`: a
    material or world thumbnail, the Preview panel) renders the same way, quietly."""
    preview = engine.is_preview
    timings = result_notes.Timings()
    try:
        start = time.perf_counter()
        scene, settings, warnings = export.convert(
            depsgraph, PREVIEW_MESHES if preview else MESHES, with_passes=not preview
        )
        timings.export_s = time.perf_counter() - start
        for warning in () if preview else warnings:
            engine.report({"WARNING"}, warning)
        if not _kernels_ready(engine, timings, kernel_features_unused(scene, settings)):
            return
        view_layer = depsgraph.view_layer
        layer = view_layer.name
        tile_writer = TileWriter(engine, layer, settings, export.passes.blender_passes(view_layer))

        def stream(tile, pixels, done, total):
            tile_writer.write(tile, pixels)
            engine.update_progress(done / total)
            engine.update_stats("", f"Whitted | Tile {done}/{total}")

        def photons(done, total):
            # the compile traces them before the first tile, when the scene needs them
            engine.update_progress(done / total)
            engine.update_stats("", f"Whitted | Caustic photons {done:,}/{total:,}")

        output = core.render(
            scene, settings, on_tile=stream, should_cancel=lambda: cancelled(engine),
            on_photons=None if preview else photons,
        )  # fmt: skip
    except core.SceneError as error:
        if not preview:  # a thumbnail the scene cannot make stays blank, without a report
            engine.report({"ERROR"}, f"Whitted: {error}")
        return
    except Exception as error:
        # Anything else is Whitted's bug, or the machine's (a full disk, a damaged cache
        # it could not heal): reported, so that `blender -b` exits 1 and writes no frame,
        # which a farm sees; raised on, Blender would write a blank frame and exit 0
        report_internal_failure(engine, "render", error)
        return
    for warning in output.warnings:
        engine.report({"WARNING"}, f"Whitted: {warning}")
    stats = output.stats
    timings.load_s, timings.kernels_from, timings.render_s = (
        stats.kernel_s,
        stats.kernel_source,
        stats.render_s,
    )
    summary = result_notes.summary_line(settings, timings, stats, output.cancelled)
    engine.update_stats("", summary)
    if not preview:
        # stdout (blender -b, farm logs) gets the figures in full: Blender prints the
        # summary there too, after "Info:"
        print(result_notes.log_line(settings, timings, stats, output.cancelled))
        print(f"Whitted: {result_notes.kernels_note(timings)}")  # for farm logs, always
        kept = warnings + [f"Whitted: {w}" for w in output.warnings]
        result_notes.keep(engine, summary, timings, kept)
        result_notes.keep_cryptomatte_manifests(engine, view_layer, scene)


def register_passes(engine, scene, view_layer) -> None:
    """What `update_render_passes` registers for a view layer: Combined and the passes its
    switches ask for, so that the Render Layers node offers them and the result holds them."""
    engine.register_pass(scene, view_layer, "Combined", 4, "RGBA", "COLOR")
    for blender_pass in export.passes.blender_passes(view_layer):
        channels = len(blender_pass.chan_id)
        engine.register_pass(
            scene, view_layer, blender_pass.name, channels, blender_pass.chan_id, blender_pass.kind
        )


def kernel_features_unused(scene, settings) -> frozenset:
    """The render features (core.kernels.features) the scene cannot use: under `blender -b`
    the warm-up compiles the render kernel without them, about half the full one's compile."""
    from ..core.compile.features import expected_features
    from ..core.driver import full_kernel_asked
    from ..core.kernels.features import FEATURES

    if full_kernel_asked():  # WHITTED_FULL_KERNEL=1: every render by the full kernel
        return frozenset()
    try:
        return frozenset(FEATURES) - expected_features(scene, settings)
    except Exception:
        # Only a hint for the warm-up: a scene the compile refuses (a broken graph, a bad
        # value) gets its clear error there, naming the object and field; until then, the
        # full kernel
        return frozenset()


def _kernels_ready(engine, timings, without=frozenset()) -> bool:
    """Wait for the kernel warm-up (started when the add-on loaded, or now: then of the
    kernel variant without the features `without`, core.jit.warmup), showing its
    steps in the render's stats and, for `blender -b`, on stdout; the wait goes into
    timings.compile_s when a compile ran (not when the kernels were in the cache already,
    or copied there from the extension's: that check is no compile, however long a busy
    machine takes over it). False if Esc was pressed meanwhile: the warm-up goes on, the
    render stops."""

    printed = []

    def show(status):
        # The render's own progress bar and header follow the compile (the tiles start the
        # bar again from 0); a first-use compile is not part of the render time
        engine.update_progress(status.fraction)
        engine.update_stats("", f"Whitted | {kernel_status.compile_progress(status)}")
        if status.text not in printed:  # stdout (blender -b): each step once
            printed.append(status.text)
            print(f"Whitted: {status.text}", flush=True)

    warmup = shared_warmup(without=without)
    start = time.perf_counter()
    warmup.start()
    compiling = warmup.status().state == "running"
    status = warmup.wait(lambda: cancelled(engine), show)
    if compiling:
        timings.compile_s = time.perf_counter() - start
        if status.state == "ready":
            show(status)  # its "kernels ready in ..." line, which ended the wait
    if status.state == "running":
        message = (
            "Whitted: render cancelled while the kernels compiled (first use on this "
            "machine); they go on compiling, and the next render starts when they are done"
        )
        engine.update_stats("", message)
        engine.report({"INFO"}, message)
        print(message, flush=True)
        return False
    if status.state == "failed":
        engine.report({"WARNING"}, f"Whitted: {status.text}; compiling in this process")
        print(f"Whitted: {status.text}; compiling in this process", flush=True)
    engine.update_stats("", "Whitted | Loading kernels")
    return True


def cancelled(engine) -> bool:
    """Esc in the UI, or a cancelled job. (A function of this module, not a bound method:
    Blender's own test_break cannot be replaced from Python, this can, by tests.)"""
    return engine.test_break()


class TileWriter:
    """Hands finished tiles to Blender: Combined and every pass the view layer asked for.
    Blender counts rows from the bottom, and from the render border's corner when there is
    one; `settings.pixel_region()` is that border (y from the top)."""

    def __init__(self, engine, layer: str, settings, blender_passes: list):
        self.engine, self.layer = engine, layer
        self.region = settings.pixel_region()
        offsets, _ = core.passes.layout(settings.passes, settings.crypto_levels)
        # (Blender's pass name, first channel after RGBA, channels) per pass
        self.passes = [
            (
                p.name,
                4 + int(offsets[core.passes.PASS_SLOT[p.core_name]]) + getattr(p, "first", 0),
                len(p.chan_id),
            )
            for p in blender_passes
        ]

    def write(self, tile, pixels) -> None:
        region_x, region_y, _, region_height = self.region
        x = tile.x - region_x
        y = region_y + region_height - tile.y - tile.height
        result = self.engine.begin_result(x, y, tile.width, tile.height, layer=self.layer)
        flipped = pixels[::-1]
        render_passes = result.layers[0].passes
        render_passes["Combined"].rect = _rows(flipped[..., :4])
        for name, first, channels in self.passes:
            render_pass = render_passes.get(name)
            if render_pass is not None:
                render_pass.rect = _rows(flipped[..., first : first + channels])
        self.engine.end_result(result)


def _rows(pixels: np.ndarray) -> np.ndarray:
    """(h, w, c) as the (w h, c) contiguous float32 rows a RenderPass's rect takes."""
    return np.ascontiguousarray(pixels, np.float32).reshape(-1, pixels.shape[2])
