"""What runs on a worker: one task's real render, in a folder of its own, by the same command
a user or a farm manager runs (`blender -b scene.blend -E WHITTED ...`, or
`python -m core render scene.lua`), its frames handed back as the bytes of their PNG files.

A task polls the job's cancel flag (a Dask Event) while its render runs and kills the render
when it is set; a render that fails raises `TaskError` with the task, the worker and the
end of the render's own log. The render dies with the worker process that started it
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

from .jobs import Border, Task

# The engine's summary line, printed by `blender -b` and the command line alike
SUMMARY = re.compile(r"render (?P<seconds>[\d.]+) s \| (?P<rays>[\d.]+) M rays")
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


def _render_border_code(task: Task) -> str:
    """Python for Blender: render only the task's border, cropped, with its threads, and print
    the border in pixels and the frame's size. The border's fractions sit half a pixel inside
    each edge, so Blender's float32 arithmetic (fraction x size, truncated) gives exactly the
    pixels asked for. A `part` is cut from the frame's size as `jobs.borders` cuts it."""
    lines = ["import bpy", "r = bpy.context.scene.render",
             "w = int(r.resolution_x * r.resolution_percentage / 100)",
             "h = int(r.resolution_y * r.resolution_percentage / 100)"]  # fmt: skip
    if task.threads:
        lines.append(f"r.threads_mode = 'FIXED'; r.threads = {task.threads}")
    if task.part is not None:
        c, r, columns, rows = task.part
        lines += [f"x0, x1 = w * {c} // {columns}, w * {c + 1} // {columns}",
                  f"y0, y1 = h * {r} // {rows}, h * {r + 1} // {rows}"]  # fmt: skip
    elif task.border is not None:
        b = task.border
        lines += [f"x0, x1, y0, y1 = {b.x}, {b.x + b.width}, {b.y}, {b.y + b.height}"]
    if task.part is not None or task.border is not None:
        lines += [
            "r.use_border = True; r.use_crop_to_border = True",
            "r.border_min_x = (x0 + 0.5) / w",
            "r.border_max_x = min(1.0, (x1 + 0.5) / w)",
            # Blender counts rows from the bottom
            "r.border_min_y = (h - y1 + 0.5) / h",
            "r.border_max_y = min(1.0, (h - y0 + 0.5) / h)",
            "print('WHITTED_FARM_BORDER', x0, y0, x1 - x0, y1 - y0, w, h, flush=True)",
        ]
    return "; ".join(lines)


BORDER_LINE = re.compile(r"WHITTED_FARM_BORDER (\d+) (\d+) (\d+) (\d+) (\d+) (\d+)")


def command(task: Task, folder: Path, addon: str = "whitted") -> list[str]:
    """The render command of a task, writing its frames into `folder`."""
    if task.kind == "lua":
        line = [sys.executable, "-m", "core", "render", task.scene, "-o", str(folder / "frame.png")]
        if task.threads:
            line += ["--threads", str(task.threads)]
        if task.border is not None:
            b = task.border
            line += ["--region", f"{b.x},{b.y},{b.width},{b.height}"]
        return line
    frames = ",".join(str(f) for f in task.frames)
    return [
        *task.blender, "-b", task.scene, "--addons", addon, "-E", "WHITTED",
        "--python-expr", _render_border_code(task),
        "-o", str(folder / "frame_######"), "-F", "PNG", "-f", frames,
    ]  # fmt: skip


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


def run_task(task: Task, cancel_event: str | None = None, addon: str = "whitted") -> TaskResult:
    """Run `task`'s render here; `cancel_event` names the job's Dask Event."""
    started = time.perf_counter()
    event = None
    if cancel_event is not None:
        from distributed import Event

        event = Event(cancel_event)
    worker = _worker_name()
    with tempfile.TemporaryDirectory(prefix="whitted-task-") as name:
        folder = Path(name)
        log_path = folder / "render.log"
        with open(log_path, "w") as log:
            render = subprocess.Popen(
                command(task, folder, addon), stdout=log, stderr=subprocess.STDOUT,
                stdin=subprocess.DEVNULL, preexec_fn=_die_with_parent, env=_environment(),
                cwd=os.path.dirname(os.path.abspath(task.scene)) or None,
            )  # fmt: skip
            try:
                while render.poll() is None:
                    if event is not None and event.is_set():
                        render.kill()
                        render.wait()
                        raise TaskError(f"{task.describe()}: cancelled")
                    time.sleep(POLL_S)
            finally:
                if render.poll() is None:
                    render.kill()
                    render.wait()
        text = log_path.read_text(errors="replace")
        frames = _frames(task, folder)
        failed = render.returncode != 0 or len(frames) != len(task.frames)
        if failed:
            tail = "\n".join(text.strip().splitlines()[-LOG_LINES:])
            raise TaskError(
                f"{task.describe()} failed on worker {worker} (exit {render.returncode}):\n{tail}"
            )
    summaries = [m.groupdict() for m in SUMMARY.finditer(text)]
    border, size = task.border, None
    found = BORDER_LINE.search(text)
    if found is not None:
        x, y, w, h, width, height = (int(g) for g in found.groups())
        border, size = Border(x, y, w, h), (width, height)
    return TaskResult(
        frames=frames,
        border=border,
        size=size,
        rays=sum(float(s["rays"]) * 1e6 for s in summaries),
        render_s=sum(float(s["seconds"]) for s in summaries),
        wall_s=time.perf_counter() - started,
        worker=worker,
    )


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


PROBE = (
    "import bpy; s = bpy.context.scene; r = s.render; "
    "print('WHITTED_FARM_SIZE', int(r.resolution_x * r.resolution_percentage / 100), "
    "int(r.resolution_y * r.resolution_percentage / 100), s.frame_start, s.frame_end, "
    "s.frame_current)"
)


def probe_scene(scene: str, blender: tuple[str, ...] = ("blender",)) -> tuple[int, ...]:
    """(width, height, first frame, last frame, current frame) of a .blend file, as a
    worker's Blender reads it: the client may have no Blender of its own."""
    done = subprocess.run([*blender, "-b", scene, "--python-expr", PROBE],
                          capture_output=True, text=True, timeout=300)  # fmt: skip
    match = re.search(r"WHITTED_FARM_SIZE (\d+) (\d+) (-?\d+) (-?\d+) (-?\d+)", done.stdout)
    if done.returncode != 0 or match is None:
        tail = "\n".join((done.stdout + done.stderr).strip().splitlines()[-LOG_LINES:])
        raise TaskError(f"{scene}: Blender on worker {_worker_name()} could not read it:\n{tail}")
    return tuple(int(g) for g in match.groups())
