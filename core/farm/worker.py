"""What runs on a worker: one task's real render, by the same Blender or command line a user
runs, its frames handed back as the bytes of their PNG files.

A .blend's task goes to a warm Blender of this worker (warm_blender.py: `blender -b` with
the add-on, kept between tasks, the scene open), which renders with Blender's own render
operator as `-f` does; `fresh=True` starts and stops one for the task alone. A CS488
script's task runs `python -m core render SCENE.lua --region ...` in a folder of its own.

A task polls the job's cancel flag (a Dask Event) while its render runs and kills the render
when it is set; a render that fails raises `TaskError` with the task, the worker and the
end of the render's own log. Renders die with the worker process that started them
(Linux: PR_SET_PDEATHSIG), so a lost worker leaves no render running.
"""

from __future__ import annotations

import ctypes
import os
import re
import signal
import socket
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass
from pathlib import Path

from . import warm_blender
from .jobs import Border, Task

# The engine's summary line, printed by `blender -b` and the command line alike (Blender
# repeats it after "Fra:" and "Info:", hence the line's start)
SUMMARY = re.compile(r"^Whitted \| .*?render (?P<seconds>[\d.]+) s \| (?P<rays>[\d.]+) M rays",
                     re.MULTILINE)  # fmt: skip
POLL_S = 0.2
LOG_LINES = 12  # of a failed render's log, in its error


class TaskError(Exception):
    """A task's render failed: the message names the task, the worker and the render's log."""


@dataclass
class TaskResult:
    frames: dict[int, bytes]  # frame -> its PNG (the border's, cropped, for a border task)
    border: Border | None  # the border rendered, in pixels (None: whole frames)
    size: tuple[int, int] | None  # the frame's width and height, when a border was rendered
    rays: float  # rays the render cast
    render_s: float  # seconds it spent rendering (its own summary)
    wall_s: float  # seconds the task took, start-up included
    worker: str


def lua_command(task: Task, folder: Path) -> list[str]:
    """The CS488 command line of a script's task, writing its image into `folder`."""
    line = [sys.executable, "-m", "core", "render", task.scene, "-o", str(folder / "frame.png")]
    if task.threads:
        line += ["--threads", str(task.threads)]
    if task.border is not None:
        b = task.border
        line += ["--region", f"{b.x},{b.y},{b.width},{b.height}"]
    return line


def _environment() -> dict:
    """The worker's environment, with this package importable (the command line's tasks run
    `python -m core` from the scene's folder)."""
    root = str(Path(__file__).resolve().parents[2])
    path = os.environ.get("PYTHONPATH", "")
    return {**os.environ, "PYTHONPATH": root + (os.pathsep + path if path else "")}


def _die_with_parent() -> None:
    """In the render's process: be killed when the worker process that started it dies."""
    if sys.platform.startswith("linux"):
        ctypes.CDLL(None, use_errno=True).prctl(1, signal.SIGKILL)  # PR_SET_PDEATHSIG


def run_task(task: Task, cancel_event: str | None = None, addon: str = "whitted",
             fresh: bool = False) -> TaskResult | None:  # fmt: skip
    """Run `task`'s render here; `cancel_event` names the job's Dask Event; `fresh`: a
    Blender of the task's own, not a warm one. None when the job was cancelled: quietly,
    not as an error each worker would log."""
    started = time.perf_counter()
    event = None
    if cancel_event is not None:
        from distributed import Event

        event = Event(cancel_event)
    cancelled = (lambda: False) if event is None else event.is_set
    try:
        with tempfile.TemporaryDirectory(prefix="whitted-task-") as name:
            if cancelled():  # a task the job's cancel found still queued
                raise warm_blender.JobCancelledError()
            if task.kind == "lua":
                frames, text, border, size = _run_script(task, Path(name), cancelled)
            else:
                frames, text, border, size = _run_blend(task, Path(name), cancelled, addon,
                                                        fresh)  # fmt: skip
    except warm_blender.JobCancelledError:
        return None
    summaries = [m.groupdict() for m in SUMMARY.finditer(text)]
    return TaskResult(
        frames=frames,
        border=border,
        size=size,
        rays=sum(float(s["rays"]) * 1e6 for s in summaries),
        render_s=sum(float(s["seconds"]) for s in summaries),
        wall_s=time.perf_counter() - started,
        worker=_worker_name(),
    )


def _failed(task: Task, log: str, why: str) -> TaskError:
    tail = "\n".join(log.strip().splitlines()[-LOG_LINES:])
    return TaskError(f"{task.describe()} failed on worker {_worker_name()} ({why}):\n{tail}")


def _run_blend(task: Task, folder: Path, cancelled, addon: str, fresh: bool):
    """(frames, log, border, frame size) of a .blend's task, rendered by a warm Blender."""
    request = {"scene": task.scene, "stamp": warm_blender.stamp(task.scene),
               "frames": list(task.frames), "part": task.part, "threads": task.threads,
               "border": None if task.border is None else list(vars(task.border).values()),
               "folder": str(folder)}  # fmt: skip
    try:
        if fresh:  # never an idle one: this task's Blender starts, and stops, with it
            blender = warm_blender.WarmBlender(task.blender, addon, _environment(),
                                               _die_with_parent)  # fmt: skip
        else:
            blender = warm_blender.borrow(task.blender, addon, _environment(), _die_with_parent)
    except warm_blender.BlenderError as error:
        raise _failed(task, "", f"Blender did not start: {error}") from None
    try:
        answer, printed = blender.render(request, cancelled, POLL_S)
    except warm_blender.BlenderError as error:
        blender.kill()  # never lent again: its state is unknown
        # The log's lines the error repeats (Blender prints the engine's error too) once
        log = [line for line in blender.tail if line.strip() not in str(error)]
        raise _failed(task, "\n".join([*log, str(error)]), "Blender's render") from None
    if fresh:
        blender.kill()
    else:
        warm_blender.give_back(blender, task.blender, addon)
    frames = _frames(task, folder)
    if len(frames) != len(task.frames):
        raise _failed(task, "\n".join(printed), "frames missing")
    border, size = task.border, None
    if answer["border"] is not None:
        x, y, w, h, width, height = answer["border"]
        border, size = Border(x, y, w, h), (width, height)
    return frames, "\n".join(printed), border, size


def _run_script(task: Task, folder: Path, cancelled):
    """(frames, log, border, None) of a CS488 script's task: its command line, run from the
    script's folder (scripts name their meshes and textures from there)."""
    log_path = folder / "render.log"
    with open(log_path, "w") as log:
        render = subprocess.Popen(
            lua_command(task, folder), stdout=log, stderr=subprocess.STDOUT,
            stdin=subprocess.DEVNULL, preexec_fn=_die_with_parent,
            env={**_environment(), "TMPDIR": str(folder)},  # a killed render's files go too
            cwd=os.path.dirname(os.path.abspath(task.scene)) or None,
        )  # fmt: skip
        try:
            while render.poll() is None:
                if cancelled():
                    raise warm_blender.JobCancelledError()
                time.sleep(POLL_S)
        finally:
            if render.poll() is None:
                render.kill()
                render.wait()
    text = log_path.read_text(errors="replace")
    frames = _frames(task, folder)
    if render.returncode != 0 or len(frames) != len(task.frames):
        raise _failed(task, text, f"exit {render.returncode}")
    return frames, text, task.border, None


def _frames(task: Task, folder: Path) -> dict[int, bytes]:
    if task.kind == "lua":
        path = folder / "frame.png"
        return {task.frames[0]: path.read_bytes()} if path.exists() else {}
    found = {}
    for frame in task.frames:
        path = folder / f"frame_{frame:06d}.png"
        if path.exists():
            found[frame] = path.read_bytes()
    return found


def _worker_name() -> str:
    try:
        from distributed import get_worker

        return get_worker().address
    except (ImportError, ValueError):
        return socket.gethostname()


def probe_scene(scene: str, blender: tuple[str, ...] = ("blender",),
                addon: str = "whitted") -> tuple[int, ...]:  # fmt: skip
    """(width, height, first frame, last frame, current frame) of a .blend file, as a
    worker's Blender reads it (the client may have no Blender of its own); the Blender
    stays warm, the scene open, for the job's tasks."""
    request = {"scene": scene, "stamp": warm_blender.stamp(scene), "probe": True}
    warm = None
    try:
        warm = warm_blender.borrow(blender, addon, _environment(), _die_with_parent)
        answer, _ = warm.render(request, lambda: False, POLL_S)
    except warm_blender.BlenderError as error:
        if warm is not None:
            warm.kill()
        raise TaskError(f"{scene}: Blender on worker {_worker_name()} could not read it: "
                        f"{error}") from None  # fmt: skip
    warm_blender.give_back(warm, blender, addon)
    return tuple(answer["probe"])
