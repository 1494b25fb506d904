"""Files a script names, hostile cases, and scripts' own text: each run as a user runs it
(`python -m core render`), ending with `error: scene.lua:LINE: ...` naming the file and the
system's reason, exit 1, no traceback, nothing written. Before, a symbolic link loop, a path
too long and a folder whose name is not UTF-8 each killed the process running the script
("this is Whitted's fault"), and a UTF-8 script with a byte-order mark failed at line 1."""

import os
import subprocess
import sys
import time

import pytest

from tests.core.cs488.test_hostile_scripts import NORMAL, run
from tests.support import ROOT

LATIN1_FOLDER = os.fsdecode(b"caf\xe9")


def loop(folder, name):
    (folder / name).symlink_to(f"{name}.2")
    (folder / f"{name}.2").symlink_to(name)


def fifo(folder, name):
    os.mkfifo(folder / name)


def dangling(folder, name):
    (folder / name).symlink_to("nowhere.obj")


def a_folder(folder, name):
    (folder / name).mkdir()


# (what the case is, the script's first line, how to make the file it names, the message)
CASES = [
    ("texture a symlink loop", "t = gr.texture('t.png', {0, 0, 0}, 1)", loop,
     "scene.lua:1: gr.texture: texture file 't.png': its path is a loop of symbolic links"),
    ("mesh a symlink loop", "m = gr.mesh('m', 'm.obj')", loop,
     "scene.lua:1: gr.mesh: mesh file 'm.obj': its path is a loop of symbolic links"),
    ("mesh path too long", "m = gr.mesh('m', '" + "d/" * 2100 + "m.obj')", None,
     "its path is too long for the file system; use a shorter one"),
    ("mesh name too long", "m = gr.mesh('m', '" + "m" * 300 + ".obj')", None,
     "its path is too long for the file system; use a shorter one"),
    ("texture a named pipe", "t = gr.texture('t.png', {0, 0, 0}, 1)", fifo,
     "scene.lua:1: gr.texture: texture file 't.png' is not a regular file"),
    ("mesh a named pipe", "m = gr.mesh('m', 'm.obj')", fifo,
     "scene.lua:1: gr.mesh: mesh file 'm.obj' is not a regular file"),
    ("mesh a link to nothing", "m = gr.mesh('m', 'm.obj')", dangling,
     "scene.lua:1: gr.mesh: mesh file 'm.obj' not found"),
    ("texture a folder", "t = gr.texture('t.png', {0, 0, 0}, 1)", a_folder,
     "scene.lua:1: gr.texture: texture file 't.png' is a folder, not a file"),
    ("mesh through a file", "m = gr.mesh('m', 'scene.lua/m.obj')", None,
     "scene.lua:1: gr.mesh: mesh file 'scene.lua/m.obj' not found"),
    ("print of bytes not UTF-8", "print('a\\255')", None,
     "scene.lua:1: print: argument 1 is not UTF-8 text"),
    ("print of a second argument not UTF-8", "x = 1\nprint('ok', 'caf\\233')", None,
     "scene.lua:2: print: argument 2 is not UTF-8 text"),
    ("__tostring giving a table", "print(setmetatable({}, {__tostring = function() "
     "return {} end}))", None, "scene.lua:1: "),
    ("string in a table not UTF-8", "gr.nh_sphere('s', {0, 0, '\\255'}, 1)", None,
     "scene.lua:1: gr.nh_sphere: a string in a table given to it is not UTF-8 text"),
]  # fmt: skip


@pytest.mark.parametrize("case, line, make, message", CASES, ids=[c[0] for c in CASES])
def test_a_file_the_script_names_is_refused_at_its_line(tmp_path, case, line, make, message):
    (tmp_path / "scene.lua").write_text(line + "\n" + NORMAL)
    if make is not None:
        make(tmp_path, line.split("'")[1] if "gr.mesh" not in line else line.split("'")[3])
    before = sorted(p.name for p in tmp_path.iterdir())
    start = time.monotonic()
    result = run(tmp_path, tmp_path / "scene.lua")
    assert time.monotonic() - start < 60
    assert result.returncode == 1, result.stdout + result.stderr
    assert "Traceback" not in result.stderr and "Whitted's fault" not in result.stderr, (
        result.stderr
    )
    last = result.stderr.strip().splitlines()[-1]
    assert last.startswith("error: scene.lua:"), last
    assert message in last, last
    assert sorted(p.name for p in tmp_path.iterdir()) == before


def test_a_folder_whose_name_is_not_utf8_is_shown_with_escapes(tmp_path):
    folder = tmp_path / LATIN1_FOLDER
    folder.mkdir()
    (folder / "scene.lua").write_text("m = gr.mesh('m', 'nope.obj')\n" + NORMAL)
    result = run(folder, folder / "scene.lua")
    assert result.returncode == 1, result.stderr
    assert "Whitted's fault" not in result.stderr
    assert "scene.lua:1: gr.mesh: mesh file 'nope.obj' not found" in result.stderr
    assert "caf\\xe9" in result.stderr  # the byte, as an escape
    (folder / "scene.lua").write_text(NORMAL)  # and a script there renders
    command = [sys.executable, "-m", "core", "render", "scene.lua"]
    environment = {**os.environ, "PYTHONPATH": str(ROOT)}
    done = subprocess.run(command, cwd=folder, capture_output=True, env=environment)
    assert done.returncode == 0, done.stderr
    assert (folder / "o.png").is_file()


def test_a_script_with_a_byte_order_mark_runs_and_counts_its_lines(tmp_path):
    (tmp_path / "scene.lua").write_bytes(b"\xef\xbb\xbf" + NORMAL.encode())
    result = run(tmp_path, tmp_path / "scene.lua")
    assert result.returncode == 0, result.stderr
    assert (tmp_path / "o.png").is_file()
    (tmp_path / "bad.lua").write_bytes(b"\xef\xbb\xbfx = 1\ngr.node()\n")
    result = run(tmp_path, tmp_path / "bad.lua")
    assert result.stderr.strip().splitlines()[-1].startswith("error: bad.lua:2: gr.node: ")
    (tmp_path / "latin.lua").write_bytes(b"\xef\xbb\xbfx = 1\n-- caf\xe9\n")
    result = run(tmp_path, tmp_path / "latin.lua")
    assert "error: latin.lua:2: byte 0xe9 is not UTF-8 text" in result.stderr


def test_print_still_prints_as_lua_does(tmp_path):
    (tmp_path / "scene.lua").write_text("print(1, 2.5, nil, true, gr.node('x'), 'caf\\u{e9}')\n"
                                        + NORMAL)  # fmt: skip
    result = run(tmp_path, tmp_path / "scene.lua")
    assert result.returncode == 0, result.stderr
    assert "1\t2.5\tnil\ttrue\tnode 'x'\tcafé" in result.stdout
