"""The rendered viewport: a 3D view in Rendered shading, rendered by Whitted coarse to fine.

Blender calls `view_update` on its main thread when the scene changed (and once at the
start), and `view_draw` whenever the view is drawn. Neither renders: `ViewportSession`
exports and compiles (milliseconds: the session's `MeshCache` re-reads only meshes whose data
changed), then hands the compiled scene to a `core.progressive.ProgressiveRender`, whose thread
renders 1/8 size first and then finer passes. A moved view (orbit, zoom, a resized area) packs
only the camera again. Blender's main thread never waits on a render: view_draw draws the
newest image there is, and a timer asks for redraws while new images come.
"""

from __future__ import annotations

import contextlib
import time
import traceback
import weakref
from dataclasses import replace

import bpy

from .. import core, export
from ..core.compile import compile_scene
from ..core.jit.warmup_process import shared_warmup
from ..core.progressive import ProgressiveRender
from . import view_texture

REDRAW_S = 0.05  # how often the timer looks for new images while a session renders
# Tiles of the last pass are drawn at most this often: each redraw of a 3D view costs Blender's
# main thread (and with software OpenGL, the cores the render needs) far more than a tile
STREAM_REDRAW_S = 0.5
_sessions = weakref.WeakSet()  # the sessions alive, for the redraw timer


class ViewportSession:
    """One 3D view's rendered shading, from its first view_update until Blender frees the
    engine (shading switched away from Rendered, the area closed, the file closed)."""

    def __init__(self, on_image=None):
        """on_image(image), if given, is called on the render thread for each new image."""
        self.meshes = export.MeshCache()
        self.warmup_text = ""
        self.renderer = ProgressiveRender(wait_ready=self._kernels_ready, on_image=on_image)
        self.scene: core.Scene | None = None  # as last exported, seen through the view
        self.settings: core.RenderSettings | None = None
        self.compiled = None
        self.view: export.view.View | None = None
        self.error: str | None = None
        self.warnings: list[str] = []
        self.exports = 0  # scene exports (view_update): each re-reads only changed meshes
        self.reframes = 0  # camera-only repacks (the view moved)
        self.changed_at = time.perf_counter()
        self.texture = view_texture.ViewTexture()
        _sessions.add(self)

    def update(self, depsgraph, view: export.view.View) -> None:
        """The scene changed: export it again and start from the coarsest pass."""
        self.view, self.changed_at = view, time.perf_counter()
        try:
            camera = export.view.camera(view, depsgraph)
            scene, render, warnings = export.convert(depsgraph, self.meshes, camera)
            settings = export.view.settings(render, view)
            compiled = compile_scene(scene, settings)
        except core.SceneError as error:
            self._fail(str(error))
            return
        except Exception as error:  # Whitted's bug: shown in the view, not raised into Blender
            traceback.print_exc()
            self._fail(f"internal error ({type(error).__name__}: {error})")
            return
        self.scene, self.settings, self.compiled = scene, settings, compiled
        self.error, self.warnings = None, warnings + compiled.warnings
        note = _photon_note(render, compiled.caustics)
        if note:  # last: what Whitted cannot honour comes first in the header
            self.warnings.append(note)
        self.exports += 1
        self.renderer.submit(compiled, scene, settings)
        keep_redrawing()

    def view_moved(self, depsgraph, view: export.view.View) -> None:
        """Only the view changed: the same compiled scene through a new camera and size."""
        self.view, self.changed_at = view, time.perf_counter()
        if self.compiled is None:  # the scene failed to export: nothing to show yet
            return
        try:
            self.scene = replace(self.scene, camera=export.view.camera(view, depsgraph))
        except core.SceneError as error:
            self._fail(str(error))
            return
        self.settings = export.view.settings(self.settings, view)
        self.reframes += 1
        self.renderer.submit(self.compiled, self.scene, self.settings)
        keep_redrawing()

    def status(self) -> str:
        """The line Blender shows in the view's corner."""
        if self.error is not None:
            return f"Whitted: {self.error}"
        if self.renderer.error is not None:
            return f"Whitted: {self.renderer.error[1]}"
        if self.warmup_text:
            return f"Whitted | {self.warmup_text}"
        image = self.renderer.latest()
        if image is None:
            return "Whitted | Rendering"
        passes = len(self.renderer.passes)
        done = image.pass_index + (1 if image.complete else 0)
        state = "Done" if done == passes and not self.renderer.busy() else "Refining"
        line = f"Whitted | {state} | pass {min(done + 1, passes)}/{passes}"
        if self.warnings:
            # What Whitted cannot honour, where the user looks at the picture
            more = f" (+{len(self.warnings) - 1} more)" if len(self.warnings) > 1 else ""
            line += f" | {self.warnings[0]}{more}"
        return line

    def needs_redraw(self) -> bool:
        """A new image to draw: a finished pass at once, streamed tiles now and then."""
        latest = self.renderer.latest()
        if latest is None or latest is self.texture.image:
            return False
        return latest.complete or time.perf_counter() - self.texture.drawn_at > STREAM_REDRAW_S

    def close(self) -> None:
        _sessions.discard(self)
        self.renderer.close()
        self.texture.free()

    def _fail(self, message: str) -> None:
        self.error = message
        self.compiled = None

    def _kernels_ready(self, cancelled) -> bool:
        """On the render thread: wait for the kernel warm-up, showing its steps in the view."""

        def show(status):
            self.warmup_text = status.text

        warmup = shared_warmup()
        warmup.start()
        status = warmup.wait(cancelled, show)
        self.warmup_text = ""
        return status.state != "running"


def view_update(engine, context, depsgraph) -> None:
    session = _session(engine)
    session.update(depsgraph, export.view.read_view(context))


def view_draw(engine, context, depsgraph) -> None:
    session = _session(engine)
    view = export.view.read_view(context)
    if view != session.view:
        session.view_moved(depsgraph, view)
    session.texture.draw(engine, depsgraph.scene, session.renderer.latest(), view)
    engine.update_stats("", session.status())


def free(engine) -> None:
    session = getattr(engine, "whitted_viewport", None)
    if session is not None:
        engine.whitted_viewport = None
        session.close()


def _session(engine) -> ViewportSession:
    session = getattr(engine, "whitted_viewport", None)
    if session is None:
        session = engine.whitted_viewport = ViewportSession()
    return session


def keep_redrawing() -> None:
    """Start the redraw timer unless it runs."""
    if not bpy.app.background and not bpy.app.timers.is_registered(_redraw_rendered_views):
        bpy.app.timers.register(_redraw_rendered_views, first_interval=REDRAW_S)


def _redraw_rendered_views():
    """Timer, on the main thread: while a session has an image not yet drawn, redraw the 3D
    views in Rendered shading (no engine is touched here: Blender may have freed it)."""
    sessions = list(_sessions)
    if not any(session.renderer.busy() or session.needs_redraw() for session in sessions):
        return None
    if not any(session.needs_redraw() for session in sessions):
        return REDRAW_S
    with contextlib.suppress(AttributeError, ReferenceError, RuntimeError):
        for window in bpy.context.window_manager.windows:
            for area in window.screen.areas:
                if area.type == "VIEW_3D" and area.spaces.active.shading.type == "RENDERED":
                    area.tag_redraw()
    return REDRAW_S


def unregister() -> None:
    if bpy.app.timers.is_registered(_redraw_rendered_views):
        bpy.app.timers.unregister(_redraw_rendered_views)
    for session in list(_sessions):
        session.close()


def _photon_note(render: core.RenderSettings, caustics) -> str:
    """What the header says when F12 traces more caustic photons than the view did (at
    most VIEWPORT_PHOTONS), or "" when it traces no more."""
    if caustics is None:
        return ""
    here = f"caustics from {caustics.traced:,} photons here"
    if render.caustic_photons == "auto":
        capped = caustics.budget is not None and caustics.budget.reason == "most"
        return f"{here}, F12 traces more (automatic)" if capped else ""
    if render.caustic_photons > caustics.traced:
        return f"{here}, F12 traces {render.caustic_photons:,}"
    return ""
