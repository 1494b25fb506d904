"""The kernel warm-up (`core.kernel_warmup`) in a process of its own, watched from this one.

numba compiles mostly in Python, holding the GIL: compiled on a thread of Blender's process it
would starve Blender's own Python (its panels, its handlers) for the whole compile. In a child
process it costs Blender nothing; the child prints one line a step, read here by a thread that
does nothing else, and this process only reads `status()` now and then. The child must run
this process's own Python with its module path, so that it compiles this `core` into the same
cache: in Blender that is Blender's binary in background mode (`sys.executable` there may be
some other Python 3.11 found on PATH, whose packages do not mix with Blender's), elsewhere
`sys.executable`. The child imports this `core` under this process's name for it and names the
`core` it imported: a different one is a failure.

A render that finds the warm-up running waits for it (polling its own cancel test); a
cancelled render leaves the child running so that the next render finds the cache filled.
If the child fails, or compiled another `core`, the caller compiles in-process instead.
"""

from __future__ import annotations

import os
import subprocess
import sys
import threading
import time
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

from .kernel_warmup import PROGRESS_PREFIX, READY_PREFIX, kernels_ready, own_core

# The child's program: import this package under this process's name for it (in Blender an
# add-on's subpackage, `bl_ext.user_default.whitted.core`), which numba records in the cache
# (core.jit), and run its warm-up. Parent packages not yet imported are stood in for by empty
# ones, so that an add-on's own __init__, which needs Blender's modules, does not run. Its two
# arguments, last on the command line: the package's name and folder.
CHILD_PROGRAM = """
import runpy, sys, types
from pathlib import Path
name, folder = sys.argv[-2], Path(sys.argv[-1])
parts = name.split(".")
if len(parts) == 1:
    sys.path.insert(0, str(folder.parent))
for depth in range(1, len(parts)):
    parent = ".".join(parts[:depth])
    if parent not in sys.modules:
        stand_in = types.ModuleType(parent)
        stand_in.__path__ = [str(folder.parents[len(parts) - depth - 1])]
        sys.modules[parent] = stand_in
runpy.run_module(name + ".kernel_warmup", run_name="__main__")
"""


def child_arguments() -> list[str]:
    """CHILD_PROGRAM's two arguments for this package."""
    return [__package__, str(Path(__file__).resolve().parent)]


@dataclass(frozen=True)
class WarmupStatus:
    state: str  # "idle", "running", "ready" or "failed"
    text: str  # the last progress line, or why it failed
    seconds: float  # since the warm-up started


def python_command() -> list[str]:
    return [sys.executable, "-c", CHILD_PROGRAM, *child_arguments()]


class WarmupProcess:
    def __init__(self, command: list[str] | None = None):
        self.command = command or python_command()
        self._lock = threading.Lock()
        self._process: subprocess.Popen | None = None
        self._state = "ready" if kernels_ready() else "idle"
        self._text = ""
        self._started = 0.0
        self._output: list[str] = []

    def start(self) -> None:
        """Start the child unless the cache is complete or a child runs or ran already (one
        that failed is not retried: the renders compile in-process instead)."""
        with self._lock:
            if self._state != "idle":
                return
            if kernels_ready():
                self._state = "ready"
                return
            env = dict(os.environ)
            env["PYTHONPATH"] = os.pathsep.join(p for p in sys.path if p and Path(p).exists())
            self._output = []
            self._started = time.perf_counter()
            try:
                self._process = subprocess.Popen(
                    self.command,
                    env=env,
                    stdin=subprocess.DEVNULL,
                    stdout=subprocess.PIPE,
                    stderr=subprocess.STDOUT,
                    text=True,
                )
            except OSError as error:
                self._state, self._text = "failed", f"could not start {self.command[0]}: {error}"
                return
            self._state, self._text = "running", "compiling kernels: starting"
            threading.Thread(target=self._read, args=(self._process,), daemon=True).start()

    def _read(self, process: subprocess.Popen) -> None:
        own, foreign = own_core(), ""
        for line in process.stdout:
            line = line.rstrip("\n")
            with self._lock:
                self._output.append(line)
                if line.startswith("Whitted: core ") and line[len("Whitted: core ") :] != own:
                    foreign = line[len("Whitted: core ") :]
                if line.startswith(PROGRESS_PREFIX) or line.startswith(READY_PREFIX):
                    self._text = line[len("Whitted: ") :]
        status = process.wait()
        with self._lock:
            if status == 0 and not foreign:
                self._state = "ready"
            else:
                self._state = "failed"
                self._text = (
                    f"the warm-up compiled another copy of Whitted ({foreign})"
                    if foreign
                    else f"the warm-up process exited with status {status}: "
                    + " | ".join(self._output[-5:])
                )

    def status(self) -> WarmupStatus:
        with self._lock:
            seconds = time.perf_counter() - self._started if self._started else 0.0
            return WarmupStatus(self._state, self._text, seconds)

    def wait(
        self,
        should_cancel: Callable[[], bool],
        on_progress: Callable[[WarmupStatus], None],
        poll_s: float = 0.1,
    ) -> WarmupStatus:
        """Wait until the child is done (or was never needed), calling on_progress on each new
        line and polling should_cancel(); returns the last status, "running" if cancelled."""
        last = ""
        while True:
            status = self.status()
            if status.state != "running":
                return status
            if status.text != last:
                last = status.text
                on_progress(status)
            if should_cancel():
                return status
            time.sleep(poll_s)


_shared: WarmupProcess | None = None


def shared_warmup(command: list[str] | None = None) -> WarmupProcess:
    """The one warm-up of this process (Blender starts it once, every render waits on it);
    `command`, given before it starts, replaces the child's command line."""
    global _shared
    if _shared is None:
        _shared = WarmupProcess(command)
    elif command and _shared.status().state == "idle":
        _shared.command = command
    return _shared
