"""One signature per kernel, whatever the scene: every scene packs into arrays of the same
numba types (dtype, rank, layout, writability), so the render kernel compiled for one scene
serves all others. A difference here is a minute-long compile for the user on the first
render of each new kind of scene."""

import os
import subprocess
import sys
from pathlib import Path

import numba
import pytest

from core import (
    RenderSettings,
)
from core.compile import compile_scene
from tests.support.scenes import one_of_each_kind as scenes
from tests.support.seed_cache import seed_shared_cache

ROOT = Path(__file__).resolve().parents[3]

pytestmark = pytest.mark.skipif(
    numba.config.DISABLE_JIT, reason="about compiled signatures: none without the JIT"
)


def numba_types(scene):
    packed = compile_scene(scene, RenderSettings(8, 8)).packed
    return {
        f"{type(group).__name__}.{name}": numba.typeof(array)
        for group in packed
        for name, array in group._asdict().items()
    }


@pytest.mark.parametrize("name", [n for n in scenes() if n != "one sphere"])
def test_every_scene_packs_into_the_same_kernel_types(name):
    reference = numba_types(scenes()["one sphere"])
    types = numba_types(scenes()[name])
    different = {f: (reference[f], t) for f, t in types.items() if reference[f] != t}
    assert not different, f"{name} packs other array types than one sphere: {different}"


# After the warm-up: kernels compiled twice for arrays of one dtype and rank that differ only
# in layout, alignment or writability, the kind of copy a scene's packing would cause. (Two
# signatures for other types, int32 and int64 indices say, are the code's own, fixed cost.)
WARM_AND_COUNT = r"""
import importlib, pkgutil, re
import numba
import core.kernels
from core.jit import warmup
warmup.main()
for info in pkgutil.iter_modules(core.kernels.__path__):
    module = importlib.import_module(f"core.kernels.{info.name}")
    for name, value in vars(module).items():
        if isinstance(value, numba.core.registry.CPUDispatcher):
            kinds = [re.sub(r"Array\(([^,]+), (\d+), [^)]*\)", r"Array(\1, \2)", str(s))
                     for s in value.signatures]
            if len(set(kinds)) < len(kinds):
                print(f"two signatures: {info.name}.{name}: {value.signatures}")
"""


# The kernels of every module that compiled anything in this process (the cache misses)
COUNT_COMPILES = """
import sys, numba
def misses(v):
    return isinstance(v, numba.core.registry.CPUDispatcher) and sum(v.stats.cache_misses.values())
compiled = sorted(f"{m}.{n}" for m, module in list(sys.modules.items()) if m.startswith("core.")
                  for n, v in vars(module).items() if misses(v))
compiled = str(compiled).replace(" ", "")
"""


@pytest.mark.first
def test_the_warmup_compiles_what_every_scene_needs_once(tmp_path):
    """The kernel warm-up, in a new process with a new kernel cache, compiles each kernel
    once (a second signature is a second compile); then each scene, rendered in a new
    process of its own, only loads from that cache. (A cold compile of its own: the shared
    test cache may hold every variant already, and then a second signature would go unseen.
    It runs first of all the tests, and in a new checkout its cache becomes the shared one's
    folder for `core`: the tests after it compile none of the warm-up's kernels again.)"""
    env = {**os.environ, "WHITTED_CACHE_DIR": str(tmp_path)}
    warm = subprocess.run(
        [sys.executable, "-c", WARM_AND_COUNT], cwd=ROOT, env=env, capture_output=True, text=True
    )
    assert warm.returncode == 0, warm.stderr
    lines = warm.stdout.splitlines()
    steps = [line for line in lines if line.startswith("Whitted: compiling kernels: ")]
    assert len(steps) >= 2 and steps[-1].startswith(
        f"Whitted: compiling kernels: {len(steps)} of {len(steps)} ("
    ), lines
    assert not [line for line in lines if line.startswith("two signatures")], lines
    assert [p.name for p in next(tmp_path.iterdir()).glob("warm-*.ok")], list(tmp_path.rglob("*"))
    sources = []
    for name in scenes():
        child = (
            "from core import RenderSettings, render\n"
            "from tests.support.scenes import one_of_each_kind as scenes\n"
            f"out = render(scenes()[{name!r}], RenderSettings(4, 4, pixel_samples=1))\n"
            f"{COUNT_COMPILES}\n"
            "print(compiled, out.stats.kernel_source)\n"
        )
        done = subprocess.run(
            [sys.executable, "-c", child], cwd=ROOT, env=env, capture_output=True, text=True
        )
        assert done.returncode == 0, done.stderr
        sources.append(" ".join(done.stdout.split()[-2:]))
    # Not the render kernel alone: no kernel of any module compiled anything (packing
    # kernels, and callees whose compiles are deferred into their callers, core.jit.deferred)
    assert sources == ["[] cache"] * len(sources), dict(zip(scenes(), sources, strict=True))
    seed_shared_cache(tmp_path, Path(os.environ["WHITTED_CACHE_DIR"]))
