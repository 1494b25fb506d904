"""The kernel warm-up as Blender shows it: started early, in the status bar while it runs.

In Blender's window the warm-up process (`core.jit.warmup_process`) starts as soon as the add-on
loads, so that the kernels are usually ready by the first F12; a timer on the main thread
reads its status twice a second and shows it in the status bar ("Whitted: compiling kernels
(first use on this machine): 37 %, 52 s") and Render Properties › Sampling. Under `blender -b`
nothing starts at load (a farm node rendering with another engine should not compile), the first
render starts it and prints the same lines.
"""

import contextlib
import threading
import traceback

import bpy

from ..core.jit import child_process
from ..core.jit.warmup_process import shared_warmup

POLL_S = 0.5


def status_text() -> str:
    """One line for the status bar, or "" when there is nothing to say."""
    status = shared_warmup().status()
    if status.state == "running":
        return f"Whitted: {compile_progress(status)}"
    if status.state == "failed":
        return "Whitted: kernel warm-up failed; the first render compiles them itself"
    return ""


def compile_progress(status) -> str:
    """ "Compiling kernels (first use on this machine, not render time): 37 %, 52 s": for the
    status bar, and for the render's header while a render waits on the compile."""
    return (
        f"Compiling kernels (first use on this machine, not render time): "
        f"{100 * status.fraction:.0f} %, {status.seconds:.0f} s"
    )


def panel_text() -> str:
    """The same, short enough for Render Properties › Sampling at its default width."""
    status = shared_warmup().status()
    if status.state == "running":
        return f"Compiling: {100 * status.fraction:.0f} %"
    if status.state == "failed":
        return "Kernel warm-up failed"
    return ""


def _show_in_windows(text: str | None) -> None:
    """Put `text` in every window's status bar (None gives the bar back to Blender), and
    redraw the Properties editors, whose render panel shows it too."""
    for window in bpy.context.window_manager.windows:
        # status_text_set finds the status bar through the context's window, which a timer
        # does not have
        with bpy.context.temp_override(window=window):
            window.workspace.status_text_set(text)
        for area in window.screen.areas:
            if area.type == "PROPERTIES":
                area.tag_redraw()


def _poll():
    """Timer: keep the status bar current while the warm-up runs; give it back once done."""
    running = shared_warmup().status().state == "running"
    # No window yet, or one closing: try again on the next tick
    with contextlib.suppress(AttributeError, RuntimeError, ReferenceError, TypeError):
        _show_in_windows(status_text() if running else None)
    if not running:
        _preload()
    return POLL_S if running else None


def _start_in_window():
    if not bpy.app.background:
        shared_warmup().start()
        if shared_warmup().status().state == "running":
            bpy.app.timers.register(_poll, first_interval=POLL_S, persistent=True)
        else:
            _preload()
    return None


def _preload():
    """Load the warmed-up kernels into Blender's process on a thread of its own (loading
    blocks no one: the first render that needs them waits for it)."""

    def load():
        try:
            from ..core.driver import preload_kernels

            preload_kernels()
        except Exception:  # the first render loads them itself, and reports what fails
            traceback.print_exc()

    if shared_warmup().status().state == "ready":
        threading.Thread(target=load, name="whitted-preload", daemon=True).start()


def blender_launcher() -> list[str] | None:
    """Blender's own binary in background mode, to run core's child processes (the kernel
    warm-up, scene scripts) with this process's module path; None for `bpy` as a Python
    module, whose interpreter is sys.executable."""
    binary = bpy.app.binary_path
    if not binary:
        return None
    return [binary, "-b", "--factory-startup", "--python-use-system-env",
            "--python-exit-code", "1", "--python-expr", child_process.PROGRAM, "--"]  # fmt: skip


def register():
    child_process.use_launcher(blender_launcher())
    # Not during register itself: Blender may still be loading its start-up file; persistent,
    # or loading a .blend given on the command line would drop it
    bpy.app.timers.register(_start_in_window, first_interval=1.0, persistent=True)


def unregister():
    for timer in (_poll, _start_in_window):
        if bpy.app.timers.is_registered(timer):
            bpy.app.timers.unregister(timer)
    with contextlib.suppress(AttributeError, RuntimeError, ReferenceError, TypeError):
        _show_in_windows(None)
