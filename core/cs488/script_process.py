"""Scene scripts run in a child process, so that no script can take its host down.

The sandbox (`sandbox`) stops what Lua can interrupt, at the script's line. Some work it
cannot: a loop in a `__gc` finalizer (Lua runs finalizers with hooks off), a backtracking
`string.find` (C code), Python working for the script while holding the GIL. So a script
runs in a child process with limits the operating system enforces, and the parent — Blender
or the command line — watches it, stays responsive, and kills it when the time limit passes
or the user cancels:

- time: the sandbox stops the script at its line once the limit passes; the parent kills the
  child a moment later if it has not ended (a C loop), and the child's CPU time is capped a
  little above the limit too (RLIMIT_CPU), should the parent itself be gone;
- memory: the Lua state holds at most the limit, and the child's address space may grow by
  at most the limit past what it held on starting (RLIMIT_AS), so Python's share counts too.

Where the operating system has no such limits (Windows) the time limit is still the parent's
to enforce and the Lua state's memory is still capped. The child prints the script's print()
lines on its stdout, marked, and leaves its outcome — the gr.render calls or the error — in
a pickle file the parent reads once the child is gone.
"""

from __future__ import annotations

import json
import pickle
import queue
import shutil
import signal
import subprocess
import tempfile
import threading
import time
from collections import deque
from collections.abc import Callable
from dataclasses import asdict
from pathlib import Path

from ..jit import child_process
from .sandbox import DEFAULT_LIMITS, ScriptError, ScriptLimits

# A line of the child's stdout that carries one print() of the script, as JSON text
PRINT_MARK = "Whitted-print: "
# How long past the time limit the parent waits for the sandbox's own message (which names
# the script's line) before it kills the child
GRACE_S = 2.0
POLL_S = 0.05
# A script still running after this long is told about, once: how to stop it, and its limit
# (a hung script would otherwise hold the caller silently for the whole limit)
NOTICE_AFTER_S = 3.0


class ScriptRun:
    """One script in its child process. Call `poll()` now and then (from a timer, say) until
    it returns True, then `result()`; `cancel()` at any time kills the child."""

    def __init__(
        self,
        path: Path,
        anywhere: bool = False,
        limits: ScriptLimits = DEFAULT_LIMITS,
        print_line: Callable[[str], None] = print,
        notice: Callable[[str], None] | None = None,
    ):
        self.path = Path(path)
        self.limits = limits
        self.print_line = print_line
        self.notice = notice
        self._noticed = False
        self._folder = Path(tempfile.mkdtemp(prefix="whitted-script-"))
        self._outcome_file = self._folder / "outcome.pickle"
        options = json.dumps({"anywhere": anywhere, "limits": asdict(limits)})
        command = child_process.command(
            "cs488.script_child", str(self.path.absolute()), str(self._outcome_file), options
        )
        self._lines: queue.Queue[str] = queue.Queue()
        self._chatter: deque[str] = deque(maxlen=20)  # the child's other output, for errors
        self._started = time.monotonic()
        self._stopped_for: str | None = None  # why the parent killed the child
        self._done = False
        self._calls = None
        self._error: str | None = None
        try:
            self._process = subprocess.Popen(
                command,
                env=child_process.environment(OPENBLAS_NUM_THREADS="1", OMP_NUM_THREADS="1"),
                stdin=subprocess.DEVNULL,
                stdout=subprocess.PIPE,
                stderr=subprocess.STDOUT,
                text=True,
                encoding="utf-8",
                errors="replace",
                **child_process.separate_session(),
            )
        except OSError as error:
            shutil.rmtree(self._folder, ignore_errors=True)
            raise ScriptError(f"{self.path.name}: cannot start {command[0]}: {error}") from None
        self._reader = threading.Thread(target=self._read, daemon=True)
        self._reader.start()

    def _read(self) -> None:
        for line in self._process.stdout:
            line = line.rstrip("\n")
            if line.startswith(PRINT_MARK):
                self._lines.put(json.loads(line[len(PRINT_MARK) :]))
            else:
                self._chatter.append(line)

    def poll(self) -> bool:
        """Pass on the script's printed lines; stop the child if it ran out of time. True
        once the script has ended, one way or another."""
        if self._done:
            return True
        self._pass_lines()
        if self._process.poll() is None:
            running = time.monotonic() - self._started
            if running > self.limits.seconds + GRACE_S:
                self._stop(f"{self.path.name}: {self.limits.time_message()}")
            elif running > NOTICE_AFTER_S and self.notice and not self._noticed:
                self._noticed = True
                self.notice(self.limits.still_running_message(self.path.name, NOTICE_AFTER_S))
            return False
        self._reader.join()
        self._pass_lines()
        self._finish()
        return True

    def _pass_lines(self) -> None:
        while True:
            try:
                line = self._lines.get_nowait()
            except queue.Empty:
                return
            self.print_line(line)

    def cancel(self) -> None:
        """Kill the child now; result() then raises ScriptError saying it was cancelled."""
        if not self._done:
            self._stop(f"{self.path.name}: cancelled")
            self._process.wait()
            self._reader.join()
            self._finish()

    def _stop(self, why: str) -> None:
        self._stopped_for = self._stopped_for or why
        if self._process.poll() is None:
            self._process.kill()

    def _finish(self) -> None:
        self._done = True
        try:
            if self._stopped_for:
                self._error = self._stopped_for
            elif self._outcome_file.is_file():
                kind, value = pickle.loads(self._outcome_file.read_bytes())
                if kind == "calls":
                    self._calls = unpacked(*value)
                else:
                    self._error = value
            else:
                self._error = self._death_message(self._process.returncode)
        finally:
            shutil.rmtree(self._folder, ignore_errors=True)

    def _death_message(self, status: int) -> str:
        """Why a child that left no outcome is gone, in the user's terms where known."""
        name = self.path.name
        # The CPU-time limit (POSIX only), and a kill not ours: the system's, out of memory
        if status == -getattr(signal, "SIGXCPU", 0):
            return f"{name}: {self.limits.time_message()}"
        if status == -getattr(signal, "SIGKILL", 0):
            return (
                f"{name}: the process running the script was killed, probably by the system "
                f"for want of memory; lower the script's memory limit with "
                f"{self.limits.memory_setting}"
            )
        # Whitted's own failure, not the script's: its traceback's last line says what
        said = [line.strip() for line in self._chatter if line.strip()]
        last = said[-1][:300] if said else "no output"
        return (
            f"{name}: the process running the script failed (status {status}): {last}; "
            "this is Whitted's fault, not the script's: please report it"
        )

    def result(self) -> list:
        """The script's gr.render calls. Raises ScriptError."""
        if not self._done:
            raise RuntimeError("the script is still running: poll() until it returns True")
        if self._error is not None:
            raise ScriptError(self._error)
        return self._calls

    def wait(self, should_cancel: Callable[[], bool] | None = None) -> list:
        """Poll until the script ends (Ctrl-C or should_cancel() kills it); its result."""
        try:
            while not self.poll():
                if should_cancel is not None and should_cancel():
                    self.cancel()
                    break
                time.sleep(POLL_S)
        except BaseException:  # KeyboardInterrupt: the child goes with us
            self.cancel()
            raise
        return self.result()


# A node's links to other nodes: lists of them, and single ones (left and right: CSG nodes)
_LIST_LINKS = ("children", "parents")
_SINGLE_LINKS = ("used_by_csg", "left", "right")


def packed(calls: list) -> tuple:
    """The calls made picklable at any depth of nesting: every node's links to other nodes
    become indices into one flat list, so that pickling never recurses along a chain of
    nodes. The nodes are unusable until `unpacked`; only the child, about to exit, packs."""
    nodes: list = []
    index: dict[int, int] = {}
    pending = [call.root for call in calls]
    while pending:
        node = pending.pop()
        if id(node) not in index:
            index[id(node)] = len(nodes)
            nodes.append(node)
            pending += _linked(node)
    for node in nodes:
        _relink(node, lambda linked: index[id(linked)])
    return calls, nodes


def unpacked(calls: list, nodes: list) -> list:
    """The calls as they were before `packed`."""
    for node in nodes:
        _relink(node, nodes.__getitem__)
    return calls


def _linked(node) -> list:
    lists = [n for field in _LIST_LINKS for n in getattr(node, field)]
    return lists + [getattr(node, f) for f in _SINGLE_LINKS if getattr(node, f, None) is not None]


def _relink(node, convert) -> None:
    for field in _LIST_LINKS:
        setattr(node, field, [convert(n) for n in getattr(node, field)])
    for field in _SINGLE_LINKS:
        if hasattr(node, field):
            linked = getattr(node, field)
            setattr(node, field, None if linked is None else convert(linked))
