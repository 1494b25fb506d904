"""Hostile scene scripts and files, each run as a user runs it (`python -m core render`, in a
process of its own, within a time limit): a clear `error: file.lua[:LINE]: ...` and exit 1,
never a traceback, nothing written, and a normal script renders afterwards."""

import os
import signal
import struct
import subprocess
import sys
import time
import zlib
from pathlib import Path

import pytest

from core.cs488.script_process import GRACE_S
from tests.support import ROOT
from tests.support.hostile import NORMAL, RENDER, run
from tests.support.terminal import ctrl_c_as_in_a_terminal


def deep_chain(levels: int) -> str:
    lines = ["r = gr.node('r')", "p = r"]
    for i in range(levels):
        lines += [f"n{i} = gr.node('n{i}')", f"p:add_child(n{i})", f"p = n{i}"]
    return "\n".join([*lines, "p:add_child(gr.sphere('s'))", RENDER]) + "\n"


def deep_csg(operands: int) -> str:
    lines = ["r = gr.node('r')", "c = gr.sphere('s0')"]
    lines += [f"c = gr.csg(c, gr.sphere('s{i}'), 'union')" for i in range(1, operands)]
    return "\n".join([*lines, "r:add_child(c)", RENDER]) + "\n"


def one_colour_png(width: int, height: int) -> bytes:
    """A PNG of one grey, written by hand: 12000 x 12000 pixels in 140 KB."""

    def chunk(kind: bytes, data: bytes) -> bytes:
        crc = zlib.crc32(kind + data) & 0xFFFFFFFF
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", crc)

    rows = zlib.compress(b"\0" * ((width + 1) * height), 9)
    header = struct.pack(">IIBBBBB", width, height, 8, 0, 0, 0, 0)
    png = chunk(b"IHDR", header) + chunk(b"IDAT", rows) + chunk(b"IEND", b"")
    return b"\x89PNG\r\n\x1a\n" + png


# (what the case is, the script's bytes, files beside it, the start of the error)
CASES = [
    ("Latin-1 byte", b"r = gr.node('r')\n-- caf\xe9\n", {},
     "error: scene.lua:2: byte 0xe9 is not UTF-8 text; save the script as UTF-8"),
    ("invalid UTF-8 argument", b"r = gr.node('\\255')\n", {},
     "error: scene.lua:1: gr.node: argument 1 is not UTF-8 text"),
    ("invalid UTF-8 inside a table", b"gr.nh_sphere('s', {0, 0, '\\255'}, 1)\n", {},
     "error: scene.lua:1: gr.nh_sphere: a string in a table given to it is not UTF-8 text"),
    ("NUL byte in a path", b"gr.mesh('m', 'a\\0b.obj')\n", {},
     "error: scene.lua:1: gr.mesh: mesh file 'a\\x00b.obj' holds a NUL byte"),
    ("OBJ index beyond 64 bits", b"gr.mesh('m', 'big.obj')\n",
     {"big.obj": b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 99999999999999999999999\n"},
     "error: scene.lua:1: gr.mesh: mesh file 'big.obj': a face corner's index is beyond"),
    ("error with a table", b"error({code = 1})\n", {},
     "error: scene.lua: error() was called with no message"),
    # 2,000 nested CSG nodes ran out of Python's stack; one tree holds at most 256 operands
    ("CSG deeper than a tree holds", deep_csg(2000).encode(), {},
     "error: scene.lua:258: gr.csg: this CSG node would hold 257 shapes; at most 256 fit"),
    # It would have unpacked to 3.5 GB of float texels
    ("texture bomb", b"t = gr.texture('bomb.png', {0, 0, 0}, 1)\n",
     {"bomb.png": one_colour_png(12000, 12000)},
     "error: scene.lua:1: gr.texture: texture file 'bomb.png' is 12000 x 12000 pixels; "
     "textures of up to 67,108,864 pixels"),
    ("output path a folder", NORMAL.replace("o.png", "taken.png").encode(), {"taken.png/": b""},
     "error: "),
]  # fmt: skip


@pytest.mark.parametrize("case, source, files, message", CASES, ids=[c[0] for c in CASES])
def test_a_hostile_script_is_a_clear_error_and_writes_nothing(tmp_path, case, source, files,
                                                              message):  # fmt: skip
    for name, data in files.items():
        if name.endswith("/"):
            (tmp_path / name).mkdir()
        else:
            (tmp_path / name).write_bytes(data)
    (tmp_path / "scene.lua").write_bytes(source)
    before = sorted(p.name for p in tmp_path.iterdir())
    result = run(tmp_path, tmp_path / "scene.lua")
    assert result.returncode == 1, result.stdout + result.stderr
    assert "Traceback" not in result.stderr, result.stderr
    assert result.stderr.strip().splitlines()[-1].startswith(message), result.stderr
    assert sorted(p.name for p in tmp_path.iterdir()) == before  # nothing written
    if case == "output path a folder":
        assert "taken.png: is a folder; name a .png file" in result.stderr


def test_a_deep_hierarchy_renders_and_a_normal_script_renders_after_the_hostile_ones(tmp_path):
    """1,500 nested nodes ran out of Python's stack (RecursionError); now they render, as
    does the deepest CSG chain a tree holds."""
    for name, source in (("deep.lua", deep_chain(1500)), ("csg.lua", deep_csg(256))):
        (tmp_path / name).write_text(source)
        result = run(tmp_path, tmp_path / name)
        assert result.returncode == 0, result.stderr[-2000:]
        assert (tmp_path / "o.png").is_file()
        (tmp_path / "o.png").unlink()
    (tmp_path / "normal.lua").write_text(NORMAL)
    assert run(tmp_path, tmp_path / "normal.lua").returncode == 0
    assert (tmp_path / "o.png").is_file()


def test_a_texture_file_too_large_is_refused_before_its_pixels_are_read(tmp_path):
    """The same limit where a scene from elsewhere names an image file (core.textures)."""
    from core import SceneError, Texture
    from core.textures import load_texture

    (tmp_path / "bomb.png").write_bytes(one_colour_png(12000, 12000))
    with pytest.raises(SceneError, match=r"material 'M': texture: .*12000 x 12000 pixels"):
        load_texture(Texture(path=tmp_path / "bomb.png"), "material 'M'")


def test_a_script_larger_than_any_scene_needs_is_refused_before_lua_reads_it(tmp_path):
    """Some scripts of hundreds of MiB made Lua abort the whole process (a PANIC)."""
    (tmp_path / "scene.lua").write_bytes(b"-- " + b"x" * (65 * 2**20) + b"\n")
    result = run(tmp_path, tmp_path / "scene.lua")
    assert result.returncode == 1, result.stderr
    assert result.stderr.strip() == (
        "error: scene.lua: the script is 65 MiB; scene scripts of up to 64 MiB are read "
        "(put large meshes in OBJ files)"
    )


@pytest.mark.parametrize(
    "source, refused",
    [
        ("gr.mesh('m', 'link.obj')", "mesh file 'link.obj' is outside the script's folder"),
        ("gr.mesh('m', '../outside.obj')", "mesh file '../outside.obj' is outside"),
        ("gr.texture('/etc/hostname', {0, 0, 0}, 1)", "texture file '/etc/hostname' is outside"),
        ("r = gr.node('r') " + RENDER.replace("'o.png'", "'../escaped.png'"),
         "file '../escaped.png' is outside the script's folder"),
    ],
)  # fmt: skip
def test_a_script_reads_and_writes_only_in_its_own_folder(tmp_path, source, refused):
    """A symbolic link out, a path up or an absolute one: refused at the script's line, and
    allowed only when the user says so on the command line."""
    (tmp_path / "outside.obj").write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")
    folder = tmp_path / "scene"
    folder.mkdir()
    (folder / "link.obj").symlink_to(tmp_path / "outside.obj")
    (folder / "scene.lua").write_text(source + "\n")
    result = run(folder, folder / "scene.lua")
    assert result.returncode == 1 and refused in result.stderr, result.stderr
    assert "--allow-outside-files lifts this" in result.stderr
    assert sorted(p.name for p in tmp_path.iterdir()) == ["outside.obj", "scene"]
    if "escaped" in source:
        allowed = run(folder, folder / "scene.lua", "--allow-outside-files")
        assert allowed.returncode == 0, allowed.stderr
        assert (tmp_path / "escaped.png").is_file()


# (what the case is, the script, the limits given, the error). Each ran past both of the
# sandbox's caps before scripts ran in a child process: the first two hung the process for
# good (Lua runs finalizers with hooks off; string.find is C), the memory case took the
# machine's memory, the 2^40-path graph would have made 2^40 shapes
LIMIT_CASES = [
    ("__gc finalizer that loops",
     "setmetatable({}, {__gc = function() while true do end end})\ncollectgarbage()\n",
     ["--script-seconds", "1.5"],
     "error: scene.lua: the script ran past its time limit of 1.5 s (is there an endless "
     "loop?); raise the limit with --script-seconds"),
    ("backtracking string.find",
     "local s = string.rep('a', 40)\n"
     "string.find(s, string.rep('a?', 40) .. string.rep('a', 40) .. 'b')\n",
     ["--script-seconds", "1.5"],
     "error: scene.lua: the script ran past its time limit of 1.5 s"),
    ("endless Lua loop", "local n = 0\nwhile true do n = n + 1 end\n",
     ["--script-seconds", "1"],
     "error: scene.lua:2: the script ran past its time limit of 1 s"),
    ("Lua memory", "local t = {}\nfor i = 1, 1e9 do t[i] = string.rep('x', 64) .. i end\n",
     ["--script-memory", "200"],
     "error: scene.lua: the script needed more than its memory limit of 200 MiB; raise the "
     "limit with --script-memory"),
    ("names of 20 MiB", "local s = string.rep('x', 20 * 2^20)\nfor i = 1, 30 do gr.node(s) end\n",
     [], "error: scene.lua:2: gr.node: argument 1 is a string of 20971520 bytes"),
    ("2^40 paths to one sphere",
     "local n = gr.sphere('s')\nfor i = 1, 40 do\n  local m = gr.node('m' .. i)\n"
     "  local a, b = gr.node('a' .. i), gr.node('b' .. i)\n  a:add_child(n)\n  b:add_child(n)\n"
     "  m:add_child(a)\n  m:add_child(b)\n  n = m\nend\n" + RENDER.replace("(r,", "(n,") + "\n",
     [], "error: scene.lua:11: gr.render: node 'm40' draws 1,099,511,627,776 shapes"),
]  # fmt: skip


@pytest.mark.parametrize("case, source, limits, message", LIMIT_CASES,
                         ids=[c[0] for c in LIMIT_CASES])  # fmt: skip
def test_a_script_past_a_limit_is_stopped_with_the_limit_named(tmp_path, case, source, limits,
                                                               message):  # fmt: skip
    (tmp_path / "scene.lua").write_text(source)
    started = time.monotonic()
    result = run(tmp_path, tmp_path / "scene.lua", *limits)
    took = time.monotonic() - started
    assert result.returncode == 1, result.stdout + result.stderr
    assert result.stderr.strip().splitlines()[-1].startswith(message), result.stderr
    assert "Traceback" not in result.stderr
    assert sorted(p.name for p in tmp_path.iterdir()) == ["scene.lua"]
    # The time limit, the parent's grace for the sandbox's own message, starting up
    assert took < 1.5 + GRACE_S + 15.0, took


def test_ctrl_c_stops_a_script_that_no_hook_can_interrupt(tmp_path):
    """The command line's Ctrl-C reaches the parent only (the child runs in a session of its
    own), which kills the child: exit 130 at once, no child left behind."""
    (tmp_path / "scene.lua").write_text(
        "setmetatable({}, {__gc = function() while true do end end})\ncollectgarbage()\n"
    )
    process = subprocess.Popen(
        [sys.executable, "-m", "core", "render", "scene.lua"], cwd=tmp_path,
        env={**os.environ, "PYTHONPATH": str(ROOT)}, stderr=subprocess.PIPE, text=True,
        preexec_fn=ctrl_c_as_in_a_terminal,
    )  # fmt: skip
    time.sleep(3.0)  # the child is in its finalizer by now
    children = _children_of(process.pid)
    assert children, "no child process runs the script"
    sent = time.monotonic()
    process.send_signal(signal.SIGINT)
    assert process.wait(timeout=10) == 130
    assert time.monotonic() - sent < 2.0
    assert "interrupted: no image written" in process.stderr.read()
    time.sleep(0.2)
    assert not [pid for pid in children if Path(f"/proc/{pid}").exists()]


def _children_of(pid: int) -> list[int]:
    found = []
    for status in Path("/proc").glob("[0-9]*/status"):
        try:
            fields = dict(line.split(":\t", 1) for line in status.read_text().splitlines())
        except (OSError, ValueError):
            continue
        if fields.get("PPid", "").strip() == str(pid):
            found.append(int(status.parent.name))
    return found
