"""The Lua sandbox scene scripts run in: what it refuses, and how its errors read."""

import pytest

from core.cs488 import sandbox
from core.cs488.sandbox import ArgumentError, ScriptError, ScriptLimits, run_script


def sized(name, size):
    if size <= 0:
        raise ArgumentError(f"'{name}': size: got {size}; use a number above 0")
    return f"{name} of {size}"


def run(tmp_path, source, limits=sandbox.DEFAULT_LIMITS, **api):
    script = tmp_path / "scene.lua"
    script.write_text(source)
    printed = []
    run_script(script, api or {"sized": sized}, print_line=printed.append, limits=limits)
    return printed


def test_gr_calls_reach_python_and_return_to_lua(tmp_path):
    printed = run(tmp_path, "local s = gr.sized('box', 3)\nprint(s, 2 ^ 3, nil, true)")
    assert printed == ["box of 3\t8.0\tnil\ttrue"]


def test_lua_51_scripts_find_unpack(tmp_path):
    assert run(tmp_path, "local a, b = unpack({1, 2})\nprint(a + b)") == ["3"]


def test_a_bad_argument_is_reported_at_the_calling_line(tmp_path):
    with pytest.raises(ScriptError) as caught:
        run(tmp_path, "gr.sized('a', 1)\n\ngr.sized('b', 0)\n")
    assert str(caught.value) == "scene.lua:3: gr.sized: 'b': size: got 0; use a number above 0"


def test_syntax_errors_name_the_line(tmp_path):
    with pytest.raises(ScriptError, match=r"^scene\.lua:2: unexpected symbol near '='"):
        run(tmp_path, "local x =\n= 2\n")


@pytest.mark.parametrize(
    "source",
    [
        "os.execute('touch pwned')",
        "io.open('/etc/passwd')",
        "require('os')",
        "dofile('/etc/passwd')",
        "loadfile('/etc/passwd')",
        "load('return 1')",
        "package.loadlib('libc.so.6', 'system')",
        "debug.sethook()",
        "python.eval('1')",
    ],
)
def test_no_way_out_of_the_sandbox(tmp_path, source):
    with pytest.raises(ScriptError, match=r"^scene\.lua:1: attempt to (index|call) a nil value"):
        run(tmp_path, source)
    assert not (tmp_path / "pwned").exists()


def test_python_objects_show_no_attributes(tmp_path):
    with pytest.raises(ScriptError, match=r"^scene\.lua:1: "):
        run(tmp_path, "local f = gr.sized.__globals__", sized=sized)


def test_endless_loops_end_at_their_line_even_under_pcall(tmp_path):
    limits = ScriptLimits(seconds=0.2)
    for source in ("while true do end", "while true do pcall(function() while 1 do end end) end"):
        with pytest.raises(ScriptError) as caught:
            run(tmp_path, source, limits)
        assert str(caught.value) == (
            "scene.lua:1: the script ran past its time limit of 0.2 s (is there an endless "
            "loop?); raise the limit with --script-seconds"
        )


def test_runaway_memory_is_an_error_naming_the_limit(tmp_path):
    limits = ScriptLimits(memory_mib=32, memory_setting="Memory Limit")
    with pytest.raises(ScriptError) as caught:
        run(tmp_path, "local t = {} for i = 1, 1e8 do t[i] = string.rep('x', 64) .. i end", limits)
    assert str(caught.value) == (
        "scene.lua: the script needed more than its memory limit of 32 MiB; raise the limit "
        "with Memory Limit"
    )


def test_a_string_longer_than_any_name_is_refused_at_its_line(tmp_path):
    """30 names of 20 MiB each stalled the process converting them; a name or file name is
    never a fraction of that."""
    source = "local big = string.rep('x', 70000)\ngr.take('ok')\ngr.take(big)\n"
    with pytest.raises(ScriptError) as caught:
        run(tmp_path, source, take=lambda *a: None)
    assert str(caught.value) == (
        "scene.lua:3: gr.take: argument 1 is a string of 70000 bytes; names and file names "
        "of up to 65536 bytes"
    )
    with pytest.raises(ScriptError, match=r"^scene\.lua:1: gr\.take: a table holds a string"):
        run(tmp_path, "gr.take({string.rep('x', 70000)})", take=lambda *a: None)


def test_a_table_shared_many_times_over_is_refused_not_expanded(tmp_path):
    """Each level holds the one below 100 times: 100^6 values, were it copied out."""
    source = (
        "local t = {1}\nfor level = 1, 6 do\n  local u = {}\n"
        "  for i = 1, 100 do u[i] = t end\n  t = u\nend\ngr.take(t)\n"
    )
    with pytest.raises(ScriptError) as caught:
        run(tmp_path, source, take=lambda *a: None)
    assert str(caught.value) == (
        "scene.lua:7: gr.take: a table given holds more than 1,000,000 values (a table used "
        "in several places counts each time)"
    )


def test_a_missing_script_is_named(tmp_path):
    with pytest.raises(ScriptError, match=r"nope\.lua: cannot read the scene script"):
        run_script(tmp_path / "nope.lua", {})


class Counter(sandbox.ScriptObject):
    lua_kind = "counter"
    lua_methods = ("add", "total")

    def __init__(self, name):
        self.name, self.count = name, 0

    def __str__(self):
        return f"Counter {self.name}"

    def add(self, amount):
        if not isinstance(amount, int):
            raise ArgumentError(f"amount: got {amount!r}; use a whole number")
        self.count += amount

    def total(self):
        return self.count


def test_objects_reach_the_script_with_their_methods(tmp_path):
    made = []

    def counter(name):
        made.append(Counter(name))
        return made[-1]

    def same(a, b):
        return a is b

    printed = run(
        tmp_path,
        "local c = gr.counter('c')\nc:add(2)\nc:add(3)\n"
        "print(c:total(), tostring(c), gr.same(c, c), gr.same(c, gr.counter('d')))",
        counter=counter,
        same=same,
    )
    assert printed == ["5\tCounter c\ttrue\tfalse"]
    assert made[0].count == 5


def test_tables_arrive_as_lists_and_dicts(tmp_path):
    seen = []
    run(tmp_path, "gr.take({1, 2.5, {3}}, {a = 'x'}, {})", take=lambda *a: seen.extend(a))
    assert seen == [[1, 2.5, [3]], {"a": "x"}, []]


@pytest.mark.parametrize(
    "source, message",
    [
        (
            "c.add(2)",
            "scene.lua:2: counter:add: call it on a counter with a colon, as counter:add(...)",
        ),
        ("c:add('x')", "scene.lua:2: counter:add: amount: got 'x'; use a whole number"),
        ("c:fly()", "scene.lua:2: counter has no method 'fly'"),
        # found by the script fuzzer: a TypeError, reported as Whitted's own failure
        ("c:add()", "scene.lua:2: counter:add: takes 1 argument (amount); got 0"),
        ("c:add(1, 2)", "scene.lua:2: counter:add: takes 1 argument (amount); got 2"),
        ("c.count = 3", "scene.lua:2: cannot set fields of a counter"),
        ("setmetatable(c, {})", "scene.lua:2: cannot change a protected metatable"),
    ],
)
def test_object_misuse_is_reported_at_its_line(tmp_path, source, message):
    with pytest.raises(ScriptError) as caught:
        run(tmp_path, f"local c = gr.counter('c')\n{source}\n", counter=Counter)
    assert str(caught.value) == message
