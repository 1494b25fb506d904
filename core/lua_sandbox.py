"""Running a CS488 scene script in a sandbox: Lua 5.4 (lupa) with no way out but `gr`.

A script sees Lua's pure functions (string, table, math, pairs, print...) and the `gr` table
the caller provides. It gets no `os`, `io`, `require`, `dofile`, `loadfile`, `load`,
`package` or `debug`, and no Python objects' attributes, so it can touch no file: meshes and
textures are read by the Python behind `gr`, which resolves their names against the script's
own folder. Memory and instruction counts are capped, so a runaway script ends with an error
instead of taking the machine.

Every failure, from a syntax error to a bad argument found by the Python behind `gr`, comes
out as one `ScriptError` whose message starts `scene.lua:LINE:`, the line of the script that
made the failing call.
"""

from collections.abc import Callable
from pathlib import Path

import lupa.lua54 as lua54

MAX_MEMORY = 512 * 2**20  # bytes the Lua state may hold
MAX_INSTRUCTIONS = 200_000_000  # a scene script builds a scene; loops past this are a bug
SAFE_GLOBALS = ("assert", "error", "getmetatable", "ipairs", "next", "pairs", "pcall",
                "rawequal", "rawget", "rawlen", "rawset", "select", "setmetatable", "tonumber",
                "tostring", "type", "xpcall", "math", "string", "table", "utf8")  # fmt: skip

# Each gr function is a Lua shim around its Python implementation, which returns
# (true, result) or (false, message): the shim raises the message at level 2, so Lua puts
# the calling line of the script in front of it.
_SHIM = """
local impl, name = ...
return function(...)
    local ok, result = impl(...)
    if not ok then error(name .. ": " .. result, 2) end
    return result
end
"""


class ScriptError(Exception):
    """A scene script that could not run as written; the message names file and line."""


class ArgumentError(Exception):
    """Raised by the Python behind `gr` for a bad call; becomes a ScriptError at the line
    of the script that made the call."""


def run_script(
    path: Path, api: dict[str, Callable], print_line: Callable[[str], None] = print
) -> None:
    """Run the script at `path` with `gr.<name>` calling api[name]. Raises ScriptError."""
    path = Path(path)
    try:
        source = path.read_text()
    except OSError as error:
        raise ScriptError(f"{path}: cannot read the scene script: {error.strerror}") from None
    runtime = lua54.LuaRuntime(
        register_eval=False,
        register_builtins=False,
        unpack_returned_tuples=True,
        attribute_filter=_no_attributes,
        max_memory=MAX_MEMORY,
    )
    lua_globals = runtime.globals()
    env = runtime.table()
    for name in SAFE_GLOBALS:
        env[name] = lua_globals[name]
    env["print"] = lambda *values: print_line("\t".join(_lua_str(v) for v in values))
    env["unpack"] = lua_globals.table.unpack  # Lua 5.1's name, which older scripts use
    env["_G"] = env
    make_shim = runtime.execute(f"return function(...) {_SHIM} end")
    gr = runtime.table()
    for name, function in api.items():
        gr[name] = make_shim(_guarded(function), f"gr.{name}")
    env["gr"] = gr
    loaded = lua_globals.load(source, f"@{path.name}", "t", env)
    chunk, problem = loaded if isinstance(loaded, tuple) else (loaded, None)
    if chunk is None:
        raise ScriptError(str(problem))
    _run(runtime, chunk)


def _run(runtime, chunk) -> None:
    """Call the chunk with the instruction cap in place. The cap is a count hook; once it
    fires every later instruction fails too, so a pcall in a loop cannot go on. Hooks are
    set and cleared from Python, so no Lua instruction of ours runs under them."""
    start_cap = runtime.execute(
        "local limit = ...\n"
        "local function stop()\n"
        "  debug.sethook(stop, '', 1)\n"
        "  error('the script ran past ' .. limit .. ' Lua instructions: is there an endless "
        "loop?', 2)\n"
        "end\n"
        "return function() debug.sethook(stop, '', limit) end",
        MAX_INSTRUCTIONS,
    )
    clear_hook = runtime.globals().debug.sethook
    start_cap()
    try:
        chunk()
    except lua54.LuaMemoryError:
        raise ScriptError(f"the script used more than {MAX_MEMORY // 2**20} MiB") from None
    except lua54.LuaError as error:
        raise ScriptError(str(error).split("\nstack traceback:")[0]) from None
    finally:
        clear_hook()


def _guarded(function: Callable) -> Callable:
    def call(*args):
        try:
            return True, function(*args)
        except ArgumentError as error:
            return False, str(error)

    return call


def _no_attributes(obj, name, is_setting):
    raise AttributeError(f"scene scripts cannot reach Python attributes ('{name}')")


def _lua_str(value) -> str:
    if value is None:
        return "nil"
    if value is True or value is False:
        return "true" if value else "false"
    return str(value)
