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

from tests.support import ROOT
from tests.support.hostile import NORMAL, assert_refused, run
from tests.support.hostile_inputs import FILE_CASES, LATIN1_FOLDER


@pytest.mark.parametrize("case, line, make, message", FILE_CASES, ids=[c[0] for c in FILE_CASES])
def test_a_file_the_script_names_is_refused_at_its_line(tmp_path, case, line, make, message):
    (tmp_path / "scene.lua").write_text(line + "\n" + NORMAL)
    if make is not None:
        make(tmp_path, line.split("'")[1] if "gr.mesh" not in line else line.split("'")[3])
    before = sorted(p.name for p in tmp_path.iterdir())
    start = time.monotonic()
    result = run(tmp_path, tmp_path / "scene.lua")
    assert time.monotonic() - start < 60
    assert_refused(result, "error: scene.lua:", message)
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
