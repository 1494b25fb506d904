"""One compile per Python and numba, whatever `core` is imported as (core.jit.cache_names):
kernels cached by a checkout's `core` load, unchanged to the bit, in a copy of `core`
imported as an extension's subpackage, compiling nothing."""

import json
import os
import shutil
import subprocess
import sys
from pathlib import Path

import numba
import numpy as np
import pytest

from core import RenderSettings, render
from core.jit.cache_folder import kernel_cache_dir
from core.jit.cache_names import OWN_PACKAGE, own_module_name
from tests.support.scenes import one_of_each_kind as scenes

ROOT = Path(__file__).resolve().parents[2]
EXTENSION = "bl_ext.some_repo.whitted.core"
SETTINGS = dict(width=6, height=5, pixel_samples=1)

# Import a copy of core under the name given (parents stood in for, as core.jit.child_process
# does), render every scene, and say what compiled and what came out
RENDER_AS = r"""
import importlib, json, sys, types
from pathlib import Path
import numba
name, folder, out = sys.argv[1], Path(sys.argv[2]), sys.argv[3]
parts = name.split(".")
for depth in range(1, len(parts)):
    stand_in = types.ModuleType(".".join(parts[:depth]))
    stand_in.__path__ = [str(folder.parents[len(parts) - depth - 1])]
    sys.modules[stand_in.__name__] = stand_in
core = importlib.import_module(name)
# The test scenes are built by `core`'s model: this one's, under both names
import pkgutil
for found in pkgutil.walk_packages(core.__path__, name + "."):
    if ".farm" not in found.name and not found.name.endswith("__main__"):
        sys.modules["core" + found.name[len(name):]] = importlib.import_module(found.name)
sys.modules["core"] = core
sys.path.insert(0, sys.argv[4])
from tests.support.scenes import one_of_each_kind as scenes
pictures = {label: core.render(scene, core.RenderSettings(**SETTINGS)).image
            for label, scene in scenes().items()}
import numpy as np
np.savez(out, **pictures)
misses = sorted(f"{m}.{n}" for m, module in list(sys.modules.items()) if m.startswith(name)
                for n, v in vars(module).items()
                if isinstance(v, numba.core.registry.CPUDispatcher)
                and sum(v.stats.cache_misses.values()))
print(json.dumps({"misses": misses, "folder": str(core.jit.cache_folder.kernel_cache_dir())}))
""".replace("SETTINGS", repr(SETTINGS))


def staged_core(tmp_path: Path, name: str) -> Path:
    folder = tmp_path.joinpath(*name.split("."))
    shutil.copytree(ROOT / "core", folder, ignore=shutil.ignore_patterns("__pycache__"))
    return folder


@pytest.mark.skipif(numba.config.DISABLE_JIT, reason="about cached kernels: none without the JIT")
def test_kernels_cached_as_core_load_as_an_extensions_core_and_render_the_same(tmp_path):
    # This process renders first, so the shared cache holds every kernel the scenes need
    ours = {label: render(scene, RenderSettings(**SETTINGS)).image
            for label, scene in scenes().items()}  # fmt: skip
    folder = staged_core(tmp_path / "stage", EXTENSION)
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
    run = subprocess.run(
        [sys.executable, "-c", RENDER_AS, EXTENSION, str(folder), str(tmp_path / "theirs.npz"),
         str(ROOT)],
        cwd=tmp_path, env=env, capture_output=True, text=True, timeout=600,
    )  # fmt: skip
    assert run.returncode == 0, run.stderr[-3000:]
    said = json.loads(run.stdout.splitlines()[-1])
    assert said["folder"] == str(kernel_cache_dir())  # the same folder, not one of its own
    assert said["misses"] == [], said  # nothing compiled: every kernel loaded
    theirs = np.load(tmp_path / "theirs.npz")
    for label, pixels in ours.items():
        assert np.array_equal(theirs[label], pixels), label


def test_a_second_core_in_one_process_keeps_a_folder_of_its_own(tmp_path):
    """Two cores in one process would each load the same cached machine code, defining its
    functions twice under one name: the second one imported compiles into its own folder."""
    folder = staged_core(tmp_path / "stage", EXTENSION)
    code = (
        "import importlib, sys, types\n"
        "from core.jit.cache_folder import kernel_cache_dir as first\n"
        f"sys.path.insert(0, {str(tmp_path / 'stage')!r})\n"
        "for parent in ('bl_ext', 'bl_ext.some_repo'):\n"
        "    sys.modules[parent] = types.ModuleType(parent)\n"
        f"sys.modules['bl_ext.some_repo'].__path__ = [{str(folder.parent.parent)!r}]\n"
        f"second = importlib.import_module({EXTENSION + '.jit.cache_folder'!r})\n"
        "print(first().name, second.kernel_cache_dir().name, second.SECOND_CORE)\n"
    )
    run = subprocess.run(
        [sys.executable, "-c", code], cwd=ROOT, capture_output=True, text=True, timeout=120
    )
    assert run.returncode == 0, run.stderr[-3000:]
    first, second, flagged = run.stdout.split()
    assert first == kernel_cache_dir().name and second != first and flagged == "True"


@pytest.mark.parametrize(
    ("cached", "here"),
    [
        ("core.kernels.layout", f"{OWN_PACKAGE}.kernels.layout"),
        ("bl_ext.user_default.whitted.core.kernels.workspace", f"{OWN_PACKAGE}.kernels.workspace"),
        ("whitted.core.vocabulary", f"{OWN_PACKAGE}.vocabulary"),
        # numba's own `core`, a module our core has not got, and other packages stay
        ("numba.core.types.containers", "numba.core.types.containers"),
        ("core.no_such_module", "core.no_such_module"),
        ("core.kernels.no_such_module", "core.kernels.no_such_module"),
        ("tests.core.kernels.test_shapes", "tests.core.kernels.test_shapes"),
        ("numpy", "numpy"),
    ],
)
def test_module_names_of_any_whitted_core_are_read_as_this_ones(cached, here):
    assert own_module_name(cached) == here
