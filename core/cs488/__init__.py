"""CS488 Lua scene scripts (the A4 modelling language and the report's extensions).

    from . import load_script
    for call in load_script("scene.lua"):      # runs the script, checking every gr call
        core.render(call.scene, call.settings)  # then save to call.output

A script's gr.render calls are collected, not rendered, while it runs: a script that fails
anywhere renders nothing.
"""

from pathlib import Path

from .commands import Commands
from .render_call import RenderCall
from .sandbox import ScriptError, run_script

__all__ = ["RenderCall", "ScriptError", "load_script"]


def load_script(path: str | Path, print_line=print, anywhere: bool = False) -> list[RenderCall]:
    """Run the script at `path`; return its gr.render calls. Raises ScriptError, whose
    message starts `scene.lua:LINE:`. Unless `anywhere`, the script reads and writes files in
    its own folder tree only."""
    path = Path(path)
    commands = Commands(path.resolve().parent, print_line, anywhere)
    run_script(path, commands.api(), print_line)
    return commands.renders
