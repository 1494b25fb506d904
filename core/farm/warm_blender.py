"""Blenders kept running on a worker between its tasks (the worker's end of
blender_addon/farm_server.py): a task borrows an idle one started with the same command and
add-on, or starts one, sends its request, and gives it back when the answer came. A Blender
that failed to answer, or whose task was cancelled, is killed, never lent again.

Each Blender is started from one long-lived thread of the worker process, because Linux's
PR_SET_PDEATHSIG fires when the *thread* that started a process ends, and Dask may end the
thread that ran a task: started there, a warm Blender could be killed between two tasks.
Started from the launcher, it dies with the worker process, and only with it.
"""

from __future__ import annotations

import atexit
import collections
import json
import os
import queue
import shutil
import subprocess
import tempfile
import threading
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

SERVER_SCRIPT = "farm_server.py"
LOG_LINES = 12
START_TIMEOUT_S = 300  # a cold numba cache compiles the kernels on first use

_launcher = ThreadPoolExecutor(max_workers=1, thread_name_prefix="whitted-blender-launcher")
_idle: dict[tuple, list[WarmBlender]] = collections.defaultdict(list)
_lock = threading.Lock()
_started: set[WarmBlender] = set()  # alive, or not yet cleared up


@atexit.register
def _stop_all() -> None:
    """The worker process is ending: its Blenders end now, and their folders go, rather
    than by the kernel's signal after it (which leaves the folders)."""
    for warm in list(_started):
        warm.kill()


class BlenderError(Exception):
    """The warm Blender's render failed (its message), or Blender itself ended."""


class JobCancelledError(Exception):
    pass


def server_script() -> Path:
    """The server script beside this checkout's `core` (blender_addon/), or in the
    installed add-on that holds this `core`."""
    here = Path(__file__).resolve().parents[2]
    for folder in (here / "blender_addon", here):
        if (folder / SERVER_SCRIPT).is_file():
            return folder / SERVER_SCRIPT
    raise FileNotFoundError(f"{SERVER_SCRIPT} is neither in {here / 'blender_addon'} nor {here}")


class WarmBlender:
    """One `blender -b --python farm_server.py` and the lines it prints."""

    def __init__(self, blender: tuple[str, ...], addon: str, env: dict, preexec_fn) -> None:
        line = [*blender, "-b", "--addons", addon, "--python", str(server_script())]
        # Blender makes a blender_XXXXXX folder in $TMPDIR and removes it only when it quits:
        # a Blender killed (with its worker, or cancelled) left it. Its own TMPDIR, removed
        # when it ends (kill, or this process's exit), leaves nothing
        self.folder = tempfile.mkdtemp(prefix="whitted-blender-")
        env = {**env, "TMPDIR": self.folder}
        try:
            self.process = _launcher.submit(
                subprocess.Popen, line, stdin=subprocess.PIPE, stdout=subprocess.PIPE,
                stderr=subprocess.STDOUT, text=True, bufsize=1, env=env, preexec_fn=preexec_fn,
            ).result()  # fmt: skip
        except OSError as error:
            shutil.rmtree(self.folder, ignore_errors=True)
            raise BlenderError(f"cannot run {' '.join(blender)!r}: {error}") from None
        _started.add(self)
        self.lines: queue.Queue[str | None] = queue.Queue()
        self.tail: collections.deque[str] = collections.deque(maxlen=LOG_LINES)
        threading.Thread(target=self._read, daemon=True, name="whitted-blender-log").start()
        self._wait_for("WHITTED_FARM_READY", lambda: False, START_TIMEOUT_S)

    def _read(self) -> None:
        for line in self.process.stdout:
            self.lines.put(line.rstrip("\n"))
        self.lines.put(None)  # Blender ended

    def alive(self) -> bool:
        return self.process.poll() is None

    def kill(self) -> None:
        if self.alive():
            self.process.kill()
        self.process.wait()
        shutil.rmtree(self.folder, ignore_errors=True)
        _started.discard(self)

    def render(self, request: dict, cancelled, poll_s: float) -> tuple[dict, list[str]]:
        """(the server's answer, the lines it printed meanwhile). Raises BlenderError, or
        JobCancelledError when `cancelled()` turned true (the render is killed with its Blender)."""
        self.process.stdin.write(json.dumps(request) + "\n")
        self.process.stdin.flush()
        return self._wait_for("WHITTED_FARM_DONE", cancelled, None, poll_s)

    def _wait_for(self, kind: str, cancelled, timeout_s, poll_s: float = 0.2):
        printed, waited = [], 0.0
        while True:
            if cancelled():
                self.kill()
                raise JobCancelledError()
            try:
                line = self.lines.get(timeout=poll_s)
            except queue.Empty:
                waited += poll_s
                if timeout_s is not None and waited > timeout_s:
                    self.kill()
                    raise BlenderError(f"Blender did not start in {timeout_s} s") from None
                continue
            if line is None:
                self.kill()  # ended: its folder goes
                log = "\n".join(self.tail)
                raise BlenderError(f"{log}\nBlender ended (exit {self.process.returncode})")
            word, _, rest = line.partition(" ")
            if word == kind:
                return json.loads(rest), printed
            if word == "WHITTED_FARM_FAILED":
                raise BlenderError(json.loads(rest)["error"])
            printed.append(line)
            self.tail.append(line)


def borrow(blender: tuple[str, ...], addon: str, env: dict, preexec_fn) -> WarmBlender:
    """An idle warm Blender started as asked, or a new one (which may raise BlenderError)."""
    key = (tuple(blender), addon)
    with _lock:
        while _idle[key]:
            found = _idle[key].pop()
            if found.alive():  # not ended on its own (idle for too long)
                return found
    return WarmBlender(blender, addon, env, preexec_fn)


def give_back(warm: WarmBlender, blender: tuple[str, ...], addon: str) -> None:
    with _lock:
        _idle[(tuple(blender), addon)].append(warm)


def stamp(scene: str) -> list[int]:
    """What tells a warm Blender the file changed since it opened it."""
    found = os.stat(scene)
    return [found.st_mtime_ns, found.st_size]
