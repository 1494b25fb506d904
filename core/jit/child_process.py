"""Running one of core's modules in a child process: the kernel warm-up
(`core.jit.warmup`) and scene scripts (`core.cs488.script_process`).

The child must run this process's own Python with its module path and import this very
`core` under this process's name for it (in Blender an add-on's subpackage,
`bl_ext.user_default.whitted.core`, which numba records in the kernel cache). In Blender the
interpreter is Blender's binary in background mode (`sys.executable` there may be another
Python 3.11 found on PATH, whose packages do not mix with Blender's): the add-on says so with
`use_launcher`. Elsewhere it is `sys.executable`.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

# The child's program. Its arguments follow MARKER, last on the command line (Blender puts
# its own before): the module to run, the package's name and folder, then the module's own.
# Parent packages not yet imported are stood in for by empty ones, so that an add-on's own
# __init__, which needs Blender's modules, does not run.
MARKER = "--whitted-child"
PROGRAM = f"""
import runpy, sys, types
from pathlib import Path
at = sys.argv.index({MARKER!r})
module, name, folder = sys.argv[at + 1], sys.argv[at + 2], Path(sys.argv[at + 3])
parts = name.split(".")
if len(parts) == 1:
    sys.path.insert(0, str(folder.parent))
for depth in range(1, len(parts)):
    parent = ".".join(parts[:depth])
    if parent not in sys.modules:
        stand_in = types.ModuleType(parent)
        stand_in.__path__ = [str(folder.parents[len(parts) - depth - 1])]
        sys.modules[parent] = stand_in
sys.argv = [module, *sys.argv[at + 4:]]
runpy.run_module(name + "." + module, run_name="__main__")
"""

# A child's own children start as it was started: the launcher travels in the environment
LAUNCHER_VARIABLE = "WHITTED_CHILD_LAUNCHER"
_launcher: list[str] | None = json.loads(os.environ.get(LAUNCHER_VARIABLE) or "null")


def use_launcher(prefix: list[str] | None) -> None:
    """What starts PROGRAM: a command line ending where PROGRAM's arguments begin (Blender:
    `[binary, "-b", ..., "--python-expr", PROGRAM, "--"]`); None for sys.executable."""
    global _launcher
    _launcher = list(prefix) if prefix else None


def program_arguments(module: str, name: str | None = None, folder: Path | None = None):
    """PROGRAM's arguments for `module` of this `core` (or of the package `name` in
    `folder`, a copy staged elsewhere)."""
    name = name or __package__.rpartition(".")[0]  # the `core` this package is in
    folder = folder or Path(__file__).resolve().parent.parent
    return [MARKER, module, name, str(folder)]


def command(module: str, *arguments: str) -> list[str]:
    """The command line running `python -m <this core>.<module> arguments...`."""
    prefix = _launcher or [sys.executable, "-c", PROGRAM]
    return [*prefix, *program_arguments(module), *arguments]


def environment(**extra: str) -> dict[str, str]:
    """This process's environment with its module path, so the child finds the same
    packages (numpy, numba, lupa: in Blender, an extension's own wheels)."""
    env = dict(os.environ)
    env["PYTHONPATH"] = os.pathsep.join(p for p in sys.path if p and Path(p).exists())
    if _launcher:
        env[LAUNCHER_VARIABLE] = json.dumps(_launcher)
    env.update(extra)
    return env


def separate_session() -> dict:
    """Popen arguments that keep the child out of the terminal's Ctrl-C: the parent decides
    when it stops (and kills it), never the keyboard directly."""
    if os.name == "nt":
        return {"creationflags": subprocess.CREATE_NEW_PROCESS_GROUP}
    return {"start_new_session": True}
