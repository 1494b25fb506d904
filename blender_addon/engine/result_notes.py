"""What a final render keeps with its picture, in a user's words: the summary line, the
render time with the kernels' start-up said apart, what Whitted could not honour, and the
Cryptomatte manifests. Blender replaces the engine's stats line with its own when the render
ends, so all of it goes into the result's metadata (the Image Editor's sidebar › Metadata;
PNG and EXR files carry it) as well as the Info log.
"""

from __future__ import annotations

from dataclasses import dataclass

from .. import core, export

# A kernel start-up shorter than this is not worth a word in the summary
NOTICEABLE_S = 0.1


@dataclass
class Timings:
    """Where a final render's wall time went, in seconds."""

    export_s: float = 0.0  # reading Blender's scene
    compile_s: float = 0.0  # waiting for the first-use kernel compile (the warm-up), if any
    load_s: float = 0.0  # loading the compiled kernels (or compiling them here, on failure)
    kernels_from: str = "memory"  # core's RenderStats.kernel_source
    render_s: float = 0.0  # rendering the tiles

    @property
    def render_time_s(self) -> float:
        """The render's own time: reading the scene and tracing it, not the kernels'
        one-time start-up."""
        return self.export_s + self.render_s


def compiled_s(timings: Timings) -> float | None:
    """The seconds a first-use kernel compile took before this render (the warm-up it waited
    for, or its own compile when the warm-up failed), or None when there was none."""
    if timings.kernels_from == "compiled":
        return timings.compile_s + timings.load_s
    return timings.compile_s if timings.compile_s > 0.0 else None


def kernels_note(timings: Timings) -> str:
    """Where the kernels came from, in words: compiled on first use, loaded from the cache,
    or already in memory."""
    compiled = compiled_s(timings)
    if compiled is not None:
        loaded = f" (then loaded from the cache in {timings.load_s:.2f} s)"
        then = loaded if timings.kernels_from == "cache" else ""
        return f"first-use kernel compile {compiled:.0f} s{then}, not in the render time"
    if timings.kernels_from == "cache":
        return f"kernels loaded from the cache in {timings.load_s:.2f} s"
    return "kernels already loaded"


def kernels_in_short(timings: Timings) -> str:
    """The kernels' start-up for the summary line ("+77 s first-use compile", "+0.19 s
    loading kernels"), or "" when it was too short to notice."""
    compiled = compiled_s(timings)
    if compiled is not None:
        return f"+{compiled:.0f} s first-use compile"
    return f"+{timings.load_s:.2f} s loading kernels" if timings.load_s >= NOTICEABLE_S else ""


def summary_line(settings, timings: Timings, stats, cancelled: bool) -> str:
    """One short line: "Whitted | 5.12 s | 320x240 | 3.1 M rays, 2 threads", then the kernels'
    start-up when it took long enough to notice, and whether the render was cancelled."""
    rays = stats.rays_traced + stats.shadow_rays
    millions = f"{rays / 1e6:.1f}" if rays >= 1e5 else f"{rays / 1e6:.2f}"
    parts = [
        "Whitted",
        f"{timings.render_time_s:.2f} s",  # first: what the sidebar's narrow column shows
        f"{settings.width}x{settings.height}",
        f"{millions} M rays, {stats.threads} threads",
    ]
    if kernels_in_short(timings):
        parts.append(kernels_in_short(timings))
    if cancelled:
        parts.append(f"cancelled after {stats.tiles_done} of {stats.tiles_total} tiles")
    return " | ".join(parts)


def log_line(settings, timings: Timings, stats, cancelled: bool) -> str:
    """The render's figures in full for `blender -b` logs, where farms and benchmarks read
    them (core.farm.worker.SUMMARY): "Whitted | 320x240 | export 0.05 s | kernels cache
    0.12 s | render 1.52 s | 3.1 M rays (1.2 M shadow), 2.04 M rays/s | 4 threads | 16/16
    tiles". The summary line is the short form of it, for the window."""
    return (
        f"Whitted | {settings.width}x{settings.height} | export {timings.export_s:.2f} s | "
        f"{stats.summary()} | {stats.tiles_done}/{stats.tiles_total} tiles"
        + (" | cancelled" if cancelled else "")
    )


def keep(engine, summary: str, timings: Timings, warnings: list[str]) -> None:
    """The summary in the Info log, then the warnings (reported last, so that the status bar
    ends on what needs the user's attention, not on the summary), and all of it in the
    result's metadata."""
    engine.report({"INFO"}, summary)
    if warnings:
        engine.report(
            {"WARNING"},
            f"{warnings[0]}"
            + (
                f" (and {len(warnings) - 1} more warnings: Info editor)"
                if len(warnings) > 1
                else ""
            ),
        )
    result = engine.get_result()
    if result is None:
        return
    # Under the key "Whitted", without saying it twice
    result.stamp_data_add_field("Whitted", summary.removeprefix("Whitted | "))
    result.stamp_data_add_field("Whitted Render Time", f"{timings.render_time_s:.2f} s")
    result.stamp_data_add_field("Whitted Kernels", kernels_note(timings))
    if warnings:
        result.stamp_data_add_field("Whitted Warnings", " | ".join(warnings))


def keep_cryptomatte_manifests(engine, view_layer, scene) -> None:
    """Each Cryptomatte layer's name, hash and manifest in the result's metadata, where
    Blender's Cryptomatte node and other compositors look for them (and multilayer EXR files
    carry them)."""
    layers = export.passes.crypto_layers(view_layer)
    result = engine.get_result()
    if not layers or result is None:
        return
    names = core.passes.crypto_names(scene)
    for core_name, layer_name in layers:
        for key, value in core.passes.crypto_metadata(layer_name, names[core_name]).items():
            result.stamp_data_add_field(key, value)
