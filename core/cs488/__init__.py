"""CS488 Lua scene scripts (the A4 modelling language and the report's extensions).

    from . import load_script
    for call in load_script("scene.lua"):      # runs the script, checking every gr call
        core.render(call.scene, call.settings)  # then save to call.output

A script's gr.render calls are collected, not rendered, while it runs: a script that fails
anywhere renders nothing. It runs in a child process within time and memory limits
(`script_process`), so that no script can hang or crash the caller.
"""

from collections.abc import Callable
from pathlib import Path

from .commands import Commands
from .render_call import RenderCall
from .sandbox import DEFAULT_LIMITS, ScriptError, ScriptLimits, run_script
from .script_process import ScriptRun

__all__ = ["RenderCall", "ScriptError", "ScriptLimits", "ScriptRun", "load_script"]


def load_script(
    path: str | Path,
    print_line=print,
    anywhere: bool = False,
    limits: ScriptLimits = DEFAULT_LIMITS,
    should_cancel: Callable[[], bool] | None = None,
    notice: Callable[[str], None] | None = None,
) -> list[RenderCall]:
    """Run the script at `path` in a child process; return its gr.render calls. Raises
    ScriptError, whose message starts `scene.lua:LINE:` (or the file alone where no line
    applies, as for a limit the process passed). Unless `anywhere`, the script reads and
    writes files in its own folder tree only. should_cancel() is polled while it runs;
    notice(text) is told once if it runs long, how to stop it and what its limit is."""
    run = ScriptRun(Path(path), anywhere, limits, print_line, notice)
    return run.wait(should_cancel)


def load_script_here(
    path: str | Path, print_line=print, anywhere: bool = False, limits=DEFAULT_LIMITS
) -> list[RenderCall]:
    """`load_script` in this very process: what the child runs."""
    path = Path(path)
    commands = Commands(path.resolve().parent, print_line, anywhere, limits.outside_setting)
    run_script(path, commands.api(), print_line, limits)
    return commands.renders
