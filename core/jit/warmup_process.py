"""The kernel warm-up (`core.jit.warmup`) in a process of its own, watched from this one.

numba compiles mostly in Python, holding the GIL: compiled on a thread of Blender's process it
would starve Blender's own Python (its panels, its handlers) for the whole compile. In a child
process it costs Blender nothing; the child prints one line a step, read here by a thread that
does nothing else, and this process only reads `status()` now and then. The child runs this
process's Python and imports this `core` under its name here (`core.jit.child_process`), so that
it compiles into the same cache; it names the `core` it imported: a different one is a
failure.

A render that finds the warm-up running waits for it (polling its own cancel test); a
cancelled render leaves the child running so that the next render finds the cache filled.
If the child fails, or compiled another `core`, the caller compiles in-process instead.
"""

from __future__ import annotations

import math
import subprocess
import threading
import time
from collections.abc import Callable
from dataclasses import dataclass

from . import child_process
from .variants import tag
from .warmup import (
    PROGRESS_PREFIX,
    READY_PREFIX,
    kernels_ready,
    own_core,
    progress_fraction,
)


@dataclass(frozen=True)
class WarmupStatus:
    state: str  # "idle", "running", "ready" or "failed"
    text: str  # the last progress line, or why it failed
    seconds: float  # since the warm-up started
    fraction: float = 0.0  # how far it is, 0 to 1 (warmup.progress_fraction)


class WarmupProcess:
    """The warm-up of the full kernel, or of the variant without the features `without`."""

    def __init__(self, command: list[str] | None = None, without: frozenset[str] = frozenset()):
        self.command = command  # None: core.jit.child_process's, decided when it starts
        self.without = frozenset(without)
        self._lock = threading.Lock()
        self._process: subprocess.Popen | None = None
        self._state = "ready" if kernels_ready(self.without) else "idle"
        self._text = ""
        self._started = 0.0
        self._line_at = 0.0  # when the last progress line came
        self._output: list[str] = []

    def start(self) -> None:
        """Start the child unless the cache is complete or a child runs or ran already (one
        that failed is not retried: the renders compile in-process instead)."""
        with self._lock:
            if self._state != "idle":
                return
            if kernels_ready(self.without):
                self._state = "ready"
                return
            variant = ["--without", tag(self.without)] if self.without else []
            command = self.command or child_process.command("jit.warmup", *variant)
            self._output = []
            self._started = time.perf_counter()
            try:
                self._process = subprocess.Popen(
                    command,
                    env=child_process.environment(),
                    stdin=subprocess.DEVNULL,
                    stdout=subprocess.PIPE,
                    stderr=subprocess.STDOUT,
                    text=True,
                )
            except OSError as error:
                self._state, self._text = "failed", f"could not start {command[0]}: {error}"
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
                    self._line_at = time.perf_counter()
                if line.startswith(READY_PREFIX) and not foreign:
                    # The child wrote its marker before this line: the cache is complete.
                    # What it does after (pruning old cache folders, its interpreter's exit
                    # with numba's and LLVM's teardown: 1.1 s of a 30 s first render) holds
                    # up no render
                    self._state = "ready"
        status = process.wait()
        with self._lock:
            if self._state == "ready":
                return
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
            now = time.perf_counter()
            seconds = now - self._started if self._started else 0.0
            if self._state == "ready":
                return WarmupStatus(self._state, self._text, seconds, 1.0)
            fraction = progress_fraction(self._text, now - self._line_at) or 0.0
            return WarmupStatus(self._state, self._text, seconds, fraction)

    def wait(
        self,
        should_cancel: Callable[[], bool],
        on_progress: Callable[[WarmupStatus], None],
        poll_s: float = 0.1,
    ) -> WarmupStatus:
        """Wait until the child is done (or was never needed), calling on_progress on each new
        line and at least once a second (for a clock and a progress bar), and polling
        should_cancel(); returns the last status, "running" if cancelled."""
        last, shown_at = "", -math.inf
        while True:
            status = self.status()
            if status.state != "running":
                return status
            if status.text != last or time.perf_counter() - shown_at >= 1.0:
                last, shown_at = status.text, time.perf_counter()
                on_progress(status)
            if should_cancel():
                return status
            time.sleep(poll_s)


_shared: WarmupProcess | None = None
_variants: dict[frozenset[str], WarmupProcess] = {}


def shared_warmup(
    command: list[str] | None = None, without: frozenset[str] = frozenset()
) -> WarmupProcess:
    """The one warm-up of the full kernel in this process (Blender's window starts it at
    load, and every render waits on it while it runs); `command`, given before it starts,
    replaces the child's command line. With `without`, a render's: the full kernel's when it
    runs or ran (it serves every scene), else the one of the variant without those features
    (`blender -b`, where nothing compiles at load)."""
    global _shared
    if _shared is None:
        _shared = WarmupProcess(command)
    elif command and _shared.status().state == "idle":
        _shared.command = command
    if not without or _shared.status().state != "idle":
        return _shared
    with _LOCK:
        if without not in _variants:
            _variants[without] = WarmupProcess(None, without)
        return _variants[without]


_LOCK = threading.Lock()
