"""Running a CS488 scene script in a sandbox: Lua 5.4 (lupa) with no way out but `gr`.

A script sees Lua's pure functions (string, table, math, pairs, print...) and the `gr` table
the caller provides. It gets no `os`, `io`, `require`, `dofile`, `loadfile`, `load`,
`package` or `debug`, and no Python objects' attributes, so it can touch no file: meshes and
textures are read by the Python behind `gr`, which resolves their names against the script's
own folder. The Lua state's memory and the script's time are capped (`ScriptLimits`), so a
runaway script ends with an error at its line; what Lua cannot interrupt (a loop in a `__gc`
finalizer, a backtracking `string.find`) is stopped by the process that runs scripts
(`script_process`), which kills its child.

Python objects a `gr` function returns (nodes, materials, lights) reach the script as Lua
tables wrapping them, whose methods are the object's `lua_methods`: `node:translate(0, 1, 0)`
calls `Node.translate(node, 0, 1, 0)`. Arguments come back to Python as plain values: numbers,
strings, booleans, None, the wrapped objects, and lists (Lua sequences) or dicts of them.

Every failure, from a syntax error to a bad argument found by the Python behind `gr`, comes
out as one `ScriptError` whose message starts `scene.lua:LINE:`, the line of the script that
made the failing call.
"""

import inspect
import re
import time
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

import lupa
import lupa.lua54 as lua54

# The lupa package answers any unknown attribute by importing its newest Lua the first time.
# Have that happen now: Blender's add-on shutdown probes every module in sys.modules for an
# attribute while iterating it, and an import then fails with "dictionary changed size".
lupa.LuaRuntime  # noqa: B018

# Lua aborts the whole process (a "PANIC") on some scripts of hundreds of MiB, before any
# limit of its own applies; no scene needs a script this large, with meshes in OBJ files
MAX_SCRIPT_BYTES = 64 * 2**20
# How often (in Lua instructions) the time limit is looked at: about a millisecond's work
CHECK_EVERY = 1_000_000
# The longest string a gr function takes (a name, a file name): each crosses into Python as a
# copy, and 30 of 20 MiB stalled the process
MAX_STRING_BYTES = 64 * 2**10
# The most values one table argument of a gr call may hold, counting a table shared by
# several others once per use: {t, t, t...} nested eight deep is billions
MAX_TABLE_VALUES = 1_000_000
SAFE_GLOBALS = ("assert", "error", "getmetatable", "ipairs", "next", "pairs", "pcall",
                "rawequal", "rawget", "rawlen", "rawset", "select", "setmetatable", "tonumber",
                "tostring", "type", "xpcall", "math", "string", "table", "utf8")  # fmt: skip

# Each gr function is a Lua shim around its Python implementation, which returns
# (true, result) or (false, message): the shim raises the message at level 2, so Lua puts
# the calling line of the script in front of it.
_SHIM = """
local impl, name, max_bytes = ...
local select, type, error, valid_utf8 = select, type, error, utf8.len
return function(...)
    -- Python takes strings as UTF-8 text: a Lua string of other bytes (a '\\255' escape) is
    -- refused here, where the calling line is known; so is one longer than any name or path
    for i = 1, select("#", ...) do
        local value = select(i, ...)
        if type(value) == "string" then
            if #value > max_bytes then
                error(name .. ": argument " .. i .. " is a string of " .. #value ..
                      " bytes; names and file names of up to " .. max_bytes .. " bytes", 2)
            end
            if not valid_utf8(value) then
                error(name .. ": argument " .. i .. " is not UTF-8 text", 2)
            end
        end
    end
    local ok, result = impl(...)
    if not ok then error(name .. ": " .. result, 2) end
    return result
end
"""


# print, in Lua: the line a script prints must be text Python can take
_PRINT = """
local print_line, max_bytes = ...
local select, tostring, error, valid_utf8, concat = select, tostring, error, utf8.len, table.concat
return function(...)
    local parts = {}
    for i = 1, select("#", ...) do
        local text = tostring((select(i, ...)))
        if type(text) ~= "string" then
            error("print: argument " .. i .. "'s __tostring did not give a string", 2)
        end
        if not valid_utf8(text) then
            error("print: argument " .. i .. " is not UTF-8 text", 2)
        end
        parts[i] = text
    end
    local line = concat(parts, "\\t")
    if #line > max_bytes then
        error("print: a line of " .. #line .. " bytes; lines of up to " .. max_bytes ..
              " bytes are printed", 2)
    end
    print_line(line)
end
"""
# The longest line a script may print (each crosses into Python and out through a pipe)
MAX_PRINT_BYTES = 1 * 2**20


def shown(text: str) -> str:
    """Text fit to print and to hand to Lua: a file name's bytes that are not UTF-8 (kept by
    Python as surrogates) written as \\xNN escapes."""
    try:
        return text.encode("utf-8", "surrogateescape").decode("utf-8", "backslashreplace")
    except UnicodeEncodeError:  # a surrogate no file name's byte makes
        return text.encode("utf-8", "backslashreplace").decode("utf-8")


# The key under which a wrapping table holds its Python object
_HANDLE = "__object"
# How deeply nested a table argument may be ({{1, 2}, {3, 4}} is 2 deep)
_MAX_NESTING = 8


@dataclass(frozen=True)
class ScriptLimits:
    """How long a script may run and how much memory it may take, and what the user calls
    the setting that raises each (named in messages: a command-line option, an import
    option)."""

    seconds: float = 120.0
    memory_mib: int = 4096
    seconds_setting: str = "--script-seconds"
    memory_setting: str = "--script-memory"
    stop_key: str = "Ctrl-C"  # what stops a running script where it runs
    # What lets a script reach files outside its folder tree (not a limit, but named so too)
    outside_setting: str = "the command line's --allow-outside-files"

    def time_message(self) -> str:
        return (
            f"the script ran past its time limit of {self.seconds:g} s (is there an endless "
            f"loop?); raise the limit with {self.seconds_setting}"
        )

    def still_running_message(self, script: str, after: float) -> str:
        """Said once a script has run `after` seconds: how to stop it, and the limit."""
        return (
            f"{script} is still running after {after:g} s: {self.stop_key} stops it; it is "
            f"stopped at {self.seconds:g} s ({self.seconds_setting} raises or lowers that)"
        )

    def memory_message(self) -> str:
        return (
            f"the script needed more than its memory limit of {self.memory_mib} MiB; raise "
            f"the limit with {self.memory_setting}"
        )


DEFAULT_LIMITS = ScriptLimits()
# The bounds of the limits a user may set: a day of script (no scene needs minutes), and 16
# TiB (past any machine; the operating system's limits overflow beyond such numbers)
MAX_SCRIPT_SECONDS = 86_400.0
MIN_SCRIPT_SECONDS = 0.1
MAX_SCRIPT_MEMORY_MIB = 2**24
MIN_SCRIPT_MEMORY_MIB = 16


class ScriptObject:
    """A Python object a scene script holds. `lua_methods` names the methods the script may
    call with a colon; `lua_kind` is how messages name it ("node", "material")."""

    lua_kind = "object"
    lua_methods: tuple[str, ...] = ()


class ScriptError(Exception):
    """A scene script that could not run as written; the message names file and line."""


class ArgumentError(Exception):
    """Raised by the Python behind `gr` for a bad call; becomes a ScriptError at the line
    of the script that made the call."""


def run_script(
    path: Path,
    api: dict[str, Callable],
    print_line: Callable[[str], None] = print,
    limits: ScriptLimits = DEFAULT_LIMITS,
) -> None:
    """Run the script at `path` with `gr.<name>` calling api[name], here, in this process
    (`script_process` runs it in a child). Raises ScriptError."""
    path = Path(path)
    deadline = time.monotonic() + limits.seconds
    try:
        size = path.stat().st_size
        if size > MAX_SCRIPT_BYTES:
            raise ScriptError(
                f"{path.name}: the script is {size / 2**20:.0f} MiB; scene scripts of up to "
                f"{MAX_SCRIPT_BYTES // 2**20} MiB are read (put large meshes in OBJ files)"
            )
        data = path.read_bytes()
    except OSError as error:
        raise ScriptError(f"{path}: cannot read the scene script: {error.strerror}") from None
    try:
        # A byte-order mark, which some Windows editors put first, is not part of the text
        source = data.removeprefix(b"\xef\xbb\xbf").decode("utf-8")
    except UnicodeDecodeError as error:
        start = error.start + (3 if data.startswith(b"\xef\xbb\xbf") else 0)
        line = data.count(b"\n", 0, start) + 1
        raise ScriptError(
            f"{path.name}:{line}: byte 0x{data[start]:02x} is not UTF-8 text; save the "
            "script as UTF-8 (Latin-1 or another encoding will not do)"
        ) from None
    runtime = lua54.LuaRuntime(
        register_eval=False,
        register_builtins=False,
        unpack_returned_tuples=True,
        attribute_filter=_no_attributes,
        max_memory=limits.memory_mib * 2**20,
    )
    lua_globals = runtime.globals()
    env = runtime.table()
    for name in SAFE_GLOBALS:
        env[name] = lua_globals[name]
    # print as Lua's own (tostring of each value, tabs between): a value that is not UTF-8
    # text is refused in Lua, at the calling line
    env["print"] = runtime.execute(_PRINT, print_line, MAX_PRINT_BYTES)
    env["unpack"] = lua_globals.table.unpack  # Lua 5.1's name, which older scripts use
    env["_G"] = env
    bridge = _Bridge(runtime)
    gr = runtime.table()
    for name, function in api.items():
        gr[name] = bridge.shim(function, f"gr.{name}")
    env["gr"] = gr
    loaded = lua_globals.load(source, f"@{path.name}", "t", env)
    chunk, problem = loaded if isinstance(loaded, tuple) else (loaded, None)
    if chunk is None:
        raise ScriptError(str(problem))
    _run(runtime, chunk, path.name, limits, deadline)


class _Bridge:
    """Carries values across: Lua arguments into Python values, `ScriptObject`s into Lua
    tables with their methods (one table per object, so identity holds in the script)."""

    def __init__(self, runtime):
        self.runtime = runtime
        self.make_shim = runtime.execute(f"return function(...) {_SHIM} end")
        self.make_wrapper = runtime.execute(_WRAPPER)
        self.tables: dict[int, object] = {}
        self.wrappers: dict[type, Callable] = {}

    def shim(self, function: Callable, name: str):
        def call(*args):
            try:
                result = function(*(self.to_python(a) for a in args))
            except ArgumentError as error:
                return False, shown(str(error))
            except UnicodeDecodeError:  # in a table argument: the shim checks only strings
                return False, "a string in a table given to it is not UTF-8 text"
            return True, self.to_lua(result)

        return self.make_shim(call, name, MAX_STRING_BYTES)

    def to_lua(self, value):
        if not isinstance(value, ScriptObject):
            return value
        table = self.tables.get(id(value))
        if table is None:
            cls = type(value)
            if cls not in self.wrappers:
                methods = self.runtime.table()
                for method in cls.lua_methods:
                    methods[method] = self.shim(
                        _method_call(cls, method), f"{cls.lua_kind}:{method}"
                    )
                self.wrappers[cls] = self.make_wrapper(methods, cls.lua_kind)
            table = self.wrappers[cls](value, str(value))
            self.tables[id(value)] = table
        return table

    def to_python(self, value):
        return _TableReader().read(value, 0)


class _TableReader:
    """One argument's tables as Python lists and dicts, within the limits of nesting, count
    and string length (a string at the top level is the shim's to check)."""

    def __init__(self):
        self.values = 0

    def read(self, value, depth):
        if isinstance(value, str) and len(value) * 4 > MAX_STRING_BYTES:  # cheap test first
            size = len(value.encode("utf-8", "surrogatepass"))
            if size > MAX_STRING_BYTES:
                raise ArgumentError(
                    f"a table holds a string of {size} bytes; names and file names of up to "
                    f"{MAX_STRING_BYTES} bytes"
                )
        if lua54.lua_type(value) != "table":
            return value
        handle = value[_HANDLE]
        if isinstance(handle, ScriptObject):
            return handle
        if depth >= _MAX_NESTING:
            raise ArgumentError(f"a table nested more than {_MAX_NESTING} deep")
        keys = list(value.keys())
        self.values += len(keys)
        if self.values > MAX_TABLE_VALUES:
            raise ArgumentError(
                f"a table given holds more than {MAX_TABLE_VALUES:,} values (a table used "
                "in several places counts each time)"
            )
        if keys == list(range(1, len(keys) + 1)):
            return [self.read(value[k], depth + 1) for k in keys]
        return {k: self.read(value[k], depth + 1) for k in keys}


# A wrapping table: the object under _HANDLE, methods through __index, nothing settable
_WRAPPER = f"""
return function(methods, kind)
    local meta = {{
        __index = function(self, key)
            local method = methods[key]
            if method == nil then
                error(kind .. " has no method '" .. tostring(key) .. "'", 2)
            end
            return method
        end,
        __newindex = function() error("cannot set fields of a " .. kind, 2) end,
        __tostring = function(self) return rawget(self, "__text") end,
        __metatable = kind,
    }}
    return function(object, text)
        return setmetatable({{ {_HANDLE} = object, __text = text }}, meta)
    end
end
"""


def _method_call(cls: type, method: str) -> Callable:
    def call(owner, *args):
        if not isinstance(owner, cls):
            raise ArgumentError(
                f"call it on a {cls.lua_kind} with a colon, as {cls.lua_kind}:{method}(...)"
            )
        bound = getattr(owner, method)
        try:  # the count of arguments, checked before the method runs
            inspect.signature(bound).bind(*args)
        except TypeError:
            wanted = [p.name for p in inspect.signature(bound).parameters.values()]
            raise ArgumentError(
                f"takes {len(wanted)} argument{'s' if len(wanted) != 1 else ''} "
                f"({', '.join(wanted)}); got {len(args)}"
            ) from None
        return bound(*args)

    return call


# The time limit as a count hook: every CHECK_EVERY instructions it reads the clock; once past
# the deadline it fails, and from then on fails at every instruction, so that a pcall in a
# loop cannot go on
_TIME_HOOK = """
local deadline, clock, every, message = ...
local sethook, error = debug.sethook, error
local function stop()
    sethook(stop, '', 1)
    error(message, 2)
end
local function check()
    if clock() > deadline then
        sethook(stop, '', 1)
        error(message, 2)
    end
end
return function() sethook(check, '', every) end
"""


def _run(runtime, chunk, script: str, limits: ScriptLimits, deadline: float) -> None:
    """Call the chunk with the time limit in place. Hooks are set and cleared from Python,
    so no Lua instruction of ours runs under them."""
    start_hook = runtime.execute(
        _TIME_HOOK, deadline, time.monotonic, CHECK_EVERY, limits.time_message()
    )
    clear_hook = runtime.globals().debug.sethook
    start_hook()
    try:
        chunk()
    except lua54.LuaMemoryError:
        raise ScriptError(f"{script}: {limits.memory_message()}") from None
    except lua54.LuaError as error:
        raise ScriptError(_error_message(str(error), script)) from None
    except UnicodeDecodeError:  # a string inside a table argument: no line to name
        raise ScriptError(f"{script}: a string given to gr is not UTF-8 text") from None
    finally:
        clear_hook()


def _error_message(text: str, script: str) -> str:
    """The script's error as `script.lua:LINE: message`. Lua adds the place only to a text
    message; for error(42) or error() it is taken from the traceback, and a table given to
    error() carries neither message nor traceback, so the file alone is named."""
    message, _, traceback = text.partition("stack traceback:")
    message = message.strip()
    if message.startswith(f"{script}:"):
        return message
    place = re.search(rf"^\s*({re.escape(script)}:\d+):", traceback, re.M)
    where = place[1] if place else script
    if not message:
        return f"{where}: error() was called with no message (a table or nil, not text)"
    return f"{where}: {message}"


def _no_attributes(obj, name, is_setting):
    raise AttributeError(f"scene scripts cannot reach Python attributes ('{name}')")
