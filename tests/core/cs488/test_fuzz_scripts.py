"""Fuzzing scene scripts: random Lua made of gr commands with random arguments (edge numbers,
strings, nested tables, nil), method calls on what earlier lines made, pcall, loops and
lines of random bytes. Each script, run as the command line runs it (in its child process,
within its limits), must end with its gr.render calls, which then render finite pixels, or
with a clear `scene.lua[:LINE]: message` — never another exception, a traceback, a hang or
Whitted's own failure.

`make test` runs a fixed-seed sample; `make fuzz` runs thousands with a random seed.
"""

import os
import re
import shutil
import time
from pathlib import Path

import numpy as np
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import core
from core.cs488 import ScriptError, ScriptLimits, load_script
from core.cs488.commands import GR_COMMANDS
from core.cs488.script_process import GRACE_S

EXAMPLES = int(os.environ.get("WHITTED_FUZZ_EXAMPLES", "25"))
DERANDOMIZE = "WHITTED_FUZZ_EXAMPLES" not in os.environ
LIMITS = ScriptLimits(seconds=10.0, memory_mib=1024)
SCENES = Path(__file__).resolve().parents[2] / "cs488_scenes"
CLEAR_ERROR = re.compile(r"^scene\.lua(:\d+)?: \S")

FUZZ = settings(
    max_examples=EXAMPLES,
    derandomize=DERANDOMIZE,
    deadline=None,
    suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large],
    database=None,
)

VARIABLES = [f"v{i}" for i in range(6)]
METHODS = ("add_child", "set_material", "set_texture", "translate", "rotate", "scale")
EDGE_NUMBERS = ["0", "-0.0", "1", "-1", "0.5", "1e-300", "1e308", "2^63", "2^53 + 1", "-2^31",
                "0/0", "1/0", "-1/0", "math.huge", "3.5", "90", "1e6"]  # fmt: skip


def lua_string(text: str) -> str:
    """Any text as a Lua literal: each UTF-8 byte as a decimal escape."""
    return '"' + "".join(f"\\{b}" for b in text.encode("utf-8")) + '"'


numbers = st.one_of(st.sampled_from(EDGE_NUMBERS), st.floats(-10, 10).map(lambda x: f"{x!r}"),
                    st.integers(-3, 20).map(str))  # fmt: skip
strings = st.one_of(
    st.sampled_from(["'s'", "'box.obj'", "'checker.png'", "'out.png'", "'x'", "'y'", "'union'",
                     "'diff'", "'intersection'", "'\\255'", "''", "'../up.obj'"]),
    st.text(max_size=8).map(lua_string),
)  # fmt: skip
atoms = st.one_of(numbers, strings, st.sampled_from(["nil", "true", "false", *VARIABLES]))


def values(depth: int = 2):
    if depth == 0:
        return atoms
    table = st.lists(values(depth - 1), max_size=4).map(lambda vs: "{" + ", ".join(vs) + "}")
    named = values(depth - 1).map(lambda v: "{a = " + v + "}")
    triple = st.lists(numbers, min_size=3, max_size=3).map(lambda vs: "{" + ", ".join(vs) + "}")
    return st.one_of(atoms, table, named, triple)


arguments = st.lists(values(), max_size=7).map(", ".join)
# Calls shaped as the manual gives them, so that scripts get past their first line
TYPICAL = {
    "node": "'n'", "joint": "'j', {0, 0, 0}, {0, 0, 0}", "sphere": "'s'", "cube": "'c'",
    "nh_sphere": "'s', {0, 0, 0}, 1", "nh_box": "'b', {0, 0, 0}, 1", "mesh": "'m', 'box.obj'",
    "torus": "'t'", "nh_torus": "'t', {0, 0, 0}, 2, 0.5", "cylinder": "'c'",
    "nh_cylinder": "'c', {0, 0, 0}, 1, 2", "cone": "'k'", "nh_cone": "'k', {0, 0, 0}, 1, 2",
    "csg": "v1, v2, 'union'", "material": "{0.5, 0.5, 0.5}, {0.5, 0.5, 0.5}, 20, 0.3, 1, 1.5",
    "texture": "'checker.png', {0.5, 0.5, 0.5}, 20", "light": "{0, 5, 5}, {1, 1, 1}, {1, 0, 0}",
    "render": "v0, 'out.png', 8, 8, {0, 0, 8}, {0, 0, -1}, {0, 1, 0}, 50, {0.1, 0.1, 0.1}, {}",
}  # fmt: skip


@st.composite
def statements(draw, depth: int = 2):
    kind = draw(st.integers(0, 9 if depth > 0 else 6))
    target = draw(st.sampled_from(VARIABLES))
    if kind <= 2:  # a command, with typical or random arguments
        command = draw(st.sampled_from(GR_COMMANDS))
        args = TYPICAL[command] if draw(st.booleans()) else draw(arguments)
        return f"{target} = gr.{command}({args})"
    if kind <= 5:  # a method call on whatever the variable holds
        method = draw(st.sampled_from(METHODS))
        args = draw(st.one_of(st.sampled_from(VARIABLES), arguments))
        return f"{target}:{method}({args})"
    if kind == 6:
        return draw(st.binary(max_size=12)).decode("latin-1").replace("\n", " ")
    inner = draw(statements(depth - 1))
    if kind == 7:
        return f"pcall(function() {inner} end)"
    if kind == 8:
        return f"for i = 1, {draw(st.integers(0, 40))} do {inner} end"
    return f"print({draw(values())})"


@st.composite
def scripts(draw) -> bytes:
    lines = ["v0 = gr.node('root')", "v1 = gr.sphere('a')", "v2 = gr.cube('b')"]
    lines += draw(st.lists(statements(), max_size=12))
    if draw(st.integers(0, 3)):
        root = draw(st.sampled_from(VARIABLES))
        lines.append(f"gr.render({TYPICAL['render'].replace('v0', root)})")
    return "\n".join(lines).encode("latin-1") + b"\n"


@FUZZ
@given(source=scripts())
def test_random_scripts_render_or_fail_clearly(tmp_path_factory, source):
    folder = tmp_path_factory.mktemp("fuzz")
    for name in ("box.obj", "checker.png"):
        shutil.copy(SCENES / name, folder / name)
    (folder / "scene.lua").write_bytes(source)
    started = time.monotonic()
    try:
        calls = load_script(folder / "scene.lua", print_line=lambda line: None, limits=LIMITS)
    except ScriptError as error:
        message = str(error)
        assert CLEAR_ERROR.match(message), message
        assert "Whitted's fault" not in message, message
        calls = []
    assert time.monotonic() - started < LIMITS.seconds + GRACE_S + 10.0
    for call in calls:  # at a size a test affords: the script's own may be any
        shrunk = call.settings
        shrunk.width, shrunk.height = min(shrunk.width, 24), min(shrunk.height, 24)
        shrunk.max_depth, shrunk.shadow_samples = min(shrunk.max_depth, 8), 1
        shrunk.pixel_samples, shrunk.threads = 1, 1
        image = core.render(call.scene, call.settings).image
        assert np.all(np.isfinite(image)) and np.all(image >= 0.0)
    assert sorted(p.name for p in folder.iterdir()) == ["box.obj", "checker.png", "scene.lua"]
