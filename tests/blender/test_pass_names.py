"""Whitted names its passes as Cycles does in each tested Blender (Blender 5.0 renamed
`IndexOB` to `Object Index`, `Env` to `Environment`...), so that compositing set-ups and
EXR readers made for Cycles find them: both engines render the same view layer, with every
pass switch on, to multilayer EXR files, and the names in the files are compared."""

import json

import pytest

from tests.support.blender34 import blender_34
from tests.support.pass_names import CYCLES_ONLY, NOT_IN_NEWER_CYCLES, WHITTED_ONLY, render_both


def assert_named_as_cycles_names(names: dict[str, set[str]]) -> None:
    cycles, whitted = names["CYCLES"], names["WHITTED"]
    assert {"Combined", "Depth", "Normal", "CryptoObject00"} <= cycles  # the probe works
    unlike = whitted - cycles - WHITTED_ONLY
    if "Shadow" not in cycles:
        unlike -= NOT_IN_NEWER_CYCLES
    assert unlike == set(), "named unlike Cycles"
    assert cycles - whitted - CYCLES_ONLY == set(), "written by Cycles, not by Whitted"


@pytest.mark.bpy
def test_pass_names_are_cycles_names_in_this_blender(bpy_with_whitted, tmp_path):
    names = render_both(bpy_with_whitted, tmp_path)
    assert_named_as_cycles_names(names)
    # What set-ups made for Blender 5 look for (and before it, its short names)
    index = "Object Index" if bpy_with_whitted.app.version >= (5, 0, 0) else "IndexOB"
    assert index in names["WHITTED"]


@pytest.mark.blender34
def test_pass_names_are_cycles_names_in_blender_34(tmp_path):
    out = tmp_path / "names.json"
    script = (
        "import bpy, json; from tests.support.pass_names import render_both; "
        f"names = render_both(bpy, {str(tmp_path)!r}); "
        f"open({str(out)!r}, 'w').write(json.dumps({{k: sorted(v) for k, v in names.items()}}))"
    )
    run = blender_34("--factory-startup", "--addons", "whitted", "--python-expr", script)
    assert out.is_file(), run.stdout[-3000:] + run.stderr[-3000:]
    names = {engine: set(found) for engine, found in json.loads(out.read_text()).items()}
    assert_named_as_cycles_names(names)
    assert "IndexOB" in names["WHITTED"]
