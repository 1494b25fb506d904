"""Callees' compiles deferred to the kernel Python calls (core.jit.deferred): the callee gets
no machine code and no cache file of its own, Python can still call it, numba functions
outside `core` are compiled as numba compiles them, and the deferral changes no result by a
bit (compared with numba's own way, WHITTED_FULL_CALLEE_COMPILES=1, on the torus's quartic
and the convex shapes' intervals, whose callees run three deep)."""

import json
import os
import shutil
import subprocess
import sys

import numpy as np

import core

ROOT = os.path.dirname(os.path.dirname(core.__file__))

# In a new cache folder: intersect_analytic (which calls torus_roots, which calls the root
# finders) from Python, on rays in every direction at the torus and the convex shapes; then
# torus_roots itself from Python; then a caller and callee of the script's own
TRACE_SHAPES = r"""
import json, pathlib, sys
import numba, numpy as np
from core.jit import deferred
from core.jit.cache_folder import kernel_cache_dir
from core.kernels import shapes
from core.kernels.torus import torus_roots

rng = np.random.default_rng(5)
kinds = [shapes.SHAPE_TORUS, shapes.SHAPE_CYLINDER, shapes.SHAPE_CONE, shapes.SHAPE_SPHERE]
rows = []
for kind in kinds:
    for _ in range(500):
        o = tuple(rng.normal(size=3) * 3.0)
        d = tuple(rng.normal(size=3))
        t, part = shapes.intersect_analytic(kind, 1.0, 0.25, o, d, 1e-9, np.inf)
        rows.append((t, part))
cached = lambda name: any(kernel_cache_dir().rglob(f"*{name}*.nbi"))
sig = torus_roots.signatures[0] if torus_roots.signatures else None
facts = {
    "callee_deferred": sig is not None and deferred.is_deferred(torus_roots, sig),
    "caller_deferred": deferred.is_deferred(shapes.intersect_analytic,
                                            shapes.intersect_analytic.signatures[0]),
    "caller_cached": cached("intersect_analytic"),
    "callee_cached": cached("torus_roots"),
}
# Python calls the callee: compiled in full now, with the same answer as through its caller
n, *roots = torus_roots((0.0, -5.0, 0.1), (0.0, 1.0, 0.0), 1.0, 0.25)
facts["callee_from_python"] = [n, *roots]
facts["callee_deferred_after"] = deferred.is_deferred(torus_roots, torus_roots.signatures[0])

@numba.njit
def inner(x):
    return x * 2.0

@numba.njit
def outer(x):
    return inner(x) + 1.0

facts["outside_core"] = outer(1.0)
facts["outside_core_deferred"] = deferred.is_deferred(inner, inner.signatures[0])
np.save(sys.argv[1], np.array(rows, dtype=float))
print(json.dumps(facts))
"""


def trace_shapes(tmp_path, name, **env):
    out = tmp_path / f"{name}.npy"
    run = subprocess.run(
        [sys.executable, "-c", TRACE_SHAPES, str(out)],
        env={**os.environ, "WHITTED_CACHE_DIR": str(tmp_path / name), **env},
        cwd=ROOT, capture_output=True, text=True, timeout=600,
    )  # fmt: skip
    assert run.returncode == 0, run.stderr[-3000:]
    return np.load(out), json.loads(run.stdout.splitlines()[-1])


def test_deferred_callees_get_no_machine_code_of_their_own_and_change_no_bit(tmp_path):
    deferring, facts = trace_shapes(tmp_path, "deferred")
    full, full_facts = trace_shapes(tmp_path, "full", WHITTED_FULL_CALLEE_COMPILES="1")

    # The callee was compiled only inside its caller, which alone went to the cache
    assert facts["callee_deferred"] and not facts["caller_deferred"]
    assert facts["caller_cached"] and not facts["callee_cached"]
    # numba's own way, for comparison: every callee compiled in full and cached
    assert not full_facts["callee_deferred"] and full_facts["callee_cached"]

    # The same crossings to the bit, and some rays did hit each shape
    assert np.array_equal(deferring, full, equal_nan=True)
    assert (deferring[:, 1] >= 0).reshape(4, -1).any(axis=1).all()

    # Python may still call a callee: it is compiled in full then. The ray from y = -5 along
    # y at height 0.1 crosses the tube (radius 0.25 about the unit circle) where its
    # half-width is sqrt(0.25^2 - 0.1^2), on both sides of the ring
    n, *roots = facts["callee_from_python"]
    assert not facts["callee_deferred_after"]
    assert facts["callee_from_python"] == full_facts["callee_from_python"]
    w = np.sqrt(0.25**2 - 0.1**2)
    expected = [5 - 1 - w, 5 - 1 + w, 5 + 1 - w, 5 + 1 + w]
    assert n == 4 and np.allclose(sorted(roots), expected, rtol=1e-12)

    # numba functions outside Whitted's core are compiled the usual way
    assert facts["outside_core"] == 3.0 and not facts["outside_core_deferred"]


# A second `core`, imported as twin.core after the first installed the hooks (as Blender's
# whitted.core beside the tests' core): its warm-up's `compile_as_callee` defers as well
TWIN = r"""
import json, sys
sys.path.insert(0, sys.argv[1])
import core.kernels.shapes  # the first `core`: installs the deferral
from twin.core.jit import deferred
from twin.core.kernels.torus import torus_roots
deferred.compile_as_callee(torus_roots, (0.0, -5.0, 0.1), (0.0, 1.0, 0.0), 1.0, 0.25)
print(json.dumps(deferred.is_deferred(torus_roots, torus_roots.signatures[0])))
"""


def test_a_second_core_in_the_process_defers_its_callees_too(tmp_path):
    twin = tmp_path / "twin"
    shutil.copytree(os.path.join(ROOT, "core"), twin / "core",
                    ignore=shutil.ignore_patterns("__pycache__"))  # fmt: skip
    (twin / "__init__.py").write_text("")
    run = subprocess.run(
        [sys.executable, "-c", TWIN, str(tmp_path)],
        env={**os.environ, "WHITTED_CACHE_DIR": str(tmp_path / "cache")},
        cwd=ROOT, capture_output=True, text=True, timeout=600,
    )  # fmt: skip
    assert run.returncode == 0, run.stderr[-3000:]
    assert json.loads(run.stdout.splitlines()[-1]) is True
