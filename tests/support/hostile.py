"""Running the command line as a user runs it against hostile input, and what every such
run must leave: a $TMPDIR of its own that ends empty, and no process of its left running.
Shared by the hostile-input corpora (tests/core/cs488/test_hostile_*.py, the output and
numeric-option tests)."""

import os
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

from tests.support import ROOT

RENDER = "gr.render(r, 'o.png', 8, 8, {0, 0, 5}, {0, 0, -1}, {0, 1, 0}, 50, {0, 0, 0}, {})"
NORMAL = "r = gr.node('r')\nr:add_child(gr.sphere('s'))\n" + RENDER + "\n"


def run(folder, *args):
    """The command line as a user runs it, with a $TMPDIR of its own and a mark in its
    environment: afterwards neither a temporary file nor a process of its may be left."""
    tmp = Path(tempfile.mkdtemp(prefix="hostile-tmp-"))
    mark = f"WHITTED_HOSTILE_CASE={tmp.name}"
    try:
        done = subprocess.run(
            [sys.executable, "-m", "core", "render", *map(str, args)],
            cwd=folder, capture_output=True, text=True, timeout=300,
            env={**os.environ, "PYTHONPATH": str(ROOT), "TMPDIR": str(tmp),
                 "WHITTED_HOSTILE_CASE": tmp.name},
        )  # fmt: skip
        assert sorted(p.name for p in tmp.iterdir()) == [], "temporary files left behind"
        assert processes_with(mark) == [], "processes left behind"
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    return done


def processes_with(variable: str) -> list[int]:
    """Processes whose environment holds `variable`."""
    found = []
    for environ in Path("/proc").glob("[0-9]*/environ"):
        try:
            if variable.encode() in environ.read_bytes().split(b"\0"):
                found.append(int(environ.parent.name))
        except OSError:  # ended meanwhile, or not ours to read
            pass
    return found


def assert_refused(result, starts: str, says: str) -> str:
    """A clear error: exit 1, no traceback and not Whitted's own failure, its last line
    starting `starts` and saying `says`. Returns that line."""
    assert result.returncode == 1, result.stdout + result.stderr
    assert "Traceback" not in result.stderr and "Whitted's fault" not in result.stderr, (
        result.stderr
    )
    last = result.stderr.strip().splitlines()[-1]
    assert last.startswith(starts) and says in last, last
    return last
