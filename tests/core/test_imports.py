"""What importing `core` costs: the scene model and the Lua language come without numba
(a script's child process and the importer only build scenes); the renderer's names load
the kernels on first use and are the functions and classes, not modules."""

import subprocess
import sys

from tests.support import ROOT

PROBE = """
import sys
import core, core.model, core.cs488, core.cs488.script_child
print("numba before", "numba" in sys.modules)
from core import render
import core.driver
print("numba after", "numba" in sys.modules, callable(core.render), core.render is render)
"""


def test_the_scene_model_and_lua_come_without_numba_and_render_loads_it():
    run = subprocess.run([sys.executable, "-c", PROBE], cwd=ROOT, capture_output=True,
                         text=True, timeout=120)  # fmt: skip
    assert run.returncode == 0, run.stderr
    assert run.stdout.split("\n")[:2] == ["numba before False", "numba after True True True"]
