"""Progressive rendering for interactive views: a coarse image first, refined to the full
settings while nothing changes; any change starts again from the coarsest pass.

One worker thread per view. `submit` hands it a compiled scene; it renders `PASSES` in order,
each at 1/scale of the view's pixels along each axis, and publishes each finished pass
enlarged to the view's size (the last pass also tile by tile, over the one before) as a
`ViewImage`. A newer `submit`, or `close`, stops the pass in flight within a pixel's rays
(the driver's cancel flag) — but for the coarsest pass, which a newer view lets finish and
publish: while a view is dragged, a submit comes with every mouse move, faster than any pass,
and cancelling each left the picture at the view before the drag until the hand stopped. So
the picture follows the hand at the coarse pass's rate, each time at the newest view then
waiting (intermediate views are dropped). Nothing here runs on the caller's thread but the
bookkeeping, so a UI that submits never waits for a render.
"""

from __future__ import annotations

import threading
import traceback
from collections.abc import Callable
from dataclasses import dataclass, replace

import numpy as np

from .compile import CompiledScene, with_frame
from .driver import RenderStats, render_compiled
from .errors import SceneError
from .model import RenderSettings, Scene


@dataclass(frozen=True)
class Pass:
    scale: int  # view pixels per rendered pixel, along each axis
    full_sampling: bool  # the settings' own camera and shadow rays; else one of each


# From a 1/8-size image (80 x 45 pixels for a 640 x 360 view: milliseconds) to the settings
PASSES = (Pass(8, False), Pass(4, False), Pass(2, False), Pass(1, False), Pass(1, True))


@dataclass(frozen=True)
class ViewImage:
    pixels: np.ndarray  # float32 (height, width, 4) linear RGBA at the view's size, row 0 on top
    generation: int  # the submit it shows
    pass_index: int  # its pass in `passes`
    complete: bool  # False while the last pass's tiles stream in
    stats: RenderStats | None  # the pass's, once complete


class ProgressiveRender:
    """The coarse-to-fine renders of one view, on a thread of its own.

    wait_ready(cancelled) -> bool, if given, runs on the worker before its first render (the
    add-on waits there for the kernel warm-up); False means cancelled. on_image(image) is
    called on the worker each time an image is published.
    """

    def __init__(
        self,
        passes: tuple[Pass, ...] = PASSES,
        wait_ready: Callable[[Callable[[], bool]], bool] | None = None,
        on_image: Callable[[ViewImage], None] | None = None,
    ):
        self.passes = passes
        self._wait_ready = wait_ready
        self._on_image = on_image
        self._wake = threading.Condition()
        self._job = None  # (generation, compiled, scene, settings) not yet started
        self._generation = 0
        self._closed = False
        self._thread = None
        self._latest: ViewImage | None = None
        self.error: tuple[int, str] | None = None  # (generation, message) of a failed render
        self.renders = 0  # passes rendered to the end, for tests

    def submit(self, compiled: CompiledScene, scene: Scene, settings: RenderSettings) -> int:
        """Render `compiled` (from `scene`, whose camera may be newer: only the frame is
        packed again) at `settings`, from the coarsest pass. Returns its generation."""
        with self._wake:
            if self._closed:
                raise RuntimeError("this progressive render is closed")
            self._generation += 1
            self._job = (self._generation, compiled, scene, settings)
            if self._thread is None:
                self._thread = threading.Thread(
                    target=self._work, name="whitted-progressive", daemon=True
                )
                self._thread.start()
            self._wake.notify()
            return self._generation

    def latest(self) -> ViewImage | None:
        return self._latest

    @property
    def generation(self) -> int:
        return self._generation

    def busy(self) -> bool:
        """Work queued or a pass short of the last one still to come."""
        latest = self._latest
        return self._job is not None or (
            self.error is None
            and (
                latest is None
                or latest.generation != self._generation
                or latest.pass_index < len(self.passes) - 1
                or not latest.complete
            )
        )

    def wait_for(self, generation: int, pass_index: int = 0, timeout: float = 60.0):
        """Block until an image of `generation` at `pass_index` or later is complete (or its
        render failed); the image, or None. For tests and benchmarks: a UI polls `latest`."""
        with self._wake:
            self._wake.wait_for(lambda: self._reached(generation, pass_index), timeout)
            image = self._latest
        if image is not None and image.generation == generation:
            return image
        return None

    def _reached(self, generation: int, pass_index: int) -> bool:
        image = self._latest
        if self.error is not None and self.error[0] >= generation:
            return True
        return (
            image is not None
            and image.generation >= generation
            and (image.generation > generation or image.pass_index >= pass_index)
            and image.complete
        )

    def close(self, timeout: float = 5.0) -> None:
        """Stop the pass in flight and the thread (within a pixel's rays)."""
        with self._wake:
            self._closed = True
            self._job = None
            self._wake.notify_all()
        if self._thread is not None:
            self._thread.join(timeout)

    def _work(self) -> None:
        ready = self._wait_ready is None
        while True:
            with self._wake:
                self._wake.wait_for(lambda: self._job is not None or self._closed)
                if self._closed:
                    return
                generation, compiled, scene, settings = self._job
                self._job = None

            def stale(generation=generation):
                return self._closed or self._generation != generation

            if not ready:
                ready = self._wait_ready(stale)
                if not ready:
                    continue
            try:
                self._render_passes(generation, compiled, scene, settings, stale)
            except SceneError as error:
                self._fail(generation, str(error))
            except Exception as error:  # a bug: shown in the view, the traceback on stderr
                traceback.print_exc()
                self._fail(generation, f"internal error ({type(error).__name__}: {error})")

    def _fail(self, generation: int, message: str) -> None:
        with self._wake:
            self.error = (generation, message)
            self._wake.notify_all()

    def _render_passes(self, generation, compiled, scene, settings, stale) -> None:
        with self._wake:
            if self.error is not None:
                self.error = None
        previous = None
        for index, step in enumerate(self.passes):
            if stale():
                return
            # The coarse first pass runs to its end whatever comes meanwhile (see above)
            finish = index == 0 and step.scale > 1
            cancel = (lambda: self._closed) if finish else stale
            small = pass_settings(settings, step)
            streamed = step.scale == 1 and previous is not None and index == len(self.passes) - 1
            base = previous.copy() if streamed else None

            def show_tile(tile, pixels, _done, _total, base=base, index=index):
                base[tile.y : tile.y + tile.height, tile.x : tile.x + tile.width] = pixels
                self._publish(ViewImage(base, generation, index, False, None), stale)

            output = render_compiled(
                with_frame(compiled, scene, small),
                small,
                on_tile=show_tile if streamed else None,
                should_cancel=cancel,
            )
            if output.cancelled or cancel():
                return
            previous = enlarged(output.image, settings)
            self.renders += 1
            self._publish(ViewImage(previous, generation, index, True, output.stats), cancel)

    def _publish(self, image: ViewImage, stale) -> None:
        with self._wake:
            if stale():
                return
            self._latest = image
            self._wake.notify_all()
        if self._on_image is not None:
            self._on_image(image)


def pass_settings(settings: RenderSettings, step: Pass) -> RenderSettings:
    """`settings` for one pass: 1/scale of the size (rounded up), the border scaled to cover
    at least the same view pixels, one camera and one shadow ray (per light, and towards the
    environment) unless full sampling."""
    width = -(-settings.width // step.scale)
    height = -(-settings.height // step.scale)
    region = None
    if settings.region is not None:
        x, y, w, h = settings.region
        x0, y0 = x * width // settings.width, y * height // settings.height
        x1 = min(width, -(-(x + w) * width // settings.width))
        y1 = min(height, -(-(y + h) * height // settings.height))
        region = (x0, y0, max(1, x1 - x0), max(1, y1 - y0))
    sampling = (
        {}
        if step.full_sampling
        else {
            "pixel_samples": 1,
            "shadow_samples": 1,
            "environment_samples": min(settings.environment_samples, 1),
        }
    )
    return replace(settings, width=width, height=height, region=region, **sampling)


def enlarged(image: np.ndarray, settings: RenderSettings) -> np.ndarray:
    """A pass's image at the view's size, each pixel repeated over the view pixels it stands
    for; outside the border, transparent."""
    height, width = image.shape[:2]
    rows = np.arange(settings.height) * height // settings.height
    columns = np.arange(settings.width) * width // settings.width
    full = image[rows[:, None], columns[None, :]]
    if settings.region is not None:
        x, y, w, h = settings.region
        inside = np.zeros(full.shape[:2], bool)
        inside[y : y + h, x : x + w] = True
        full[~inside] = 0.0
    return full
