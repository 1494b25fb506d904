"""The list of Blender versions tested (tests/blender/versions.py) and the Makefile's, which
builds their environments and runs their tests, agree; and finding a Python skips ones that
do not run (pyenv's shims)."""

import re
import stat

from tests.blender.versions import BPY_VERSIONS, IN_PROJECT_VENV, ROOT, python_for


def test_the_makefile_builds_and_tests_every_listed_bpy_version():
    makefile = (ROOT / "Makefile").read_text()
    listed = re.search(r"^BPY_VERSIONS := (.*)$", makefile, re.M).group(1).split()
    assert listed == [v.blender for v in BPY_VERSIONS if v.blender != IN_PROJECT_VENV]


def test_a_python_that_does_not_run_or_is_another_version_is_passed_over(tmp_path, monkeypatch):
    refuses = tmp_path / "python3.13"
    refuses.write_text("#!/bin/sh\necho 'pyenv: python3.13: command not found' >&2\nexit 127\n")
    refuses.chmod(refuses.stat().st_mode | stat.S_IXUSR)
    monkeypatch.setenv("PATH", str(tmp_path))
    monkeypatch.setenv("PYENV_ROOT", str(tmp_path / "no_pyenv"))
    monkeypatch.setenv("PYTHON313", str(refuses))
    found = python_for("3.13")
    assert found != str(refuses)
    assert found is None or found.startswith("/usr")
