"""Kernel caches that move (core.jit.relocatable, core.jit.cache_folder): a cache filled where
`core` lies in one folder loads, without compiling, where a copy of `core` with new file
times lies in another; kernels compile for the portable x86-64-v3 level on CPUs that have
it (or for the CPU the user names); the extension's shipped kernels are copied into the
user's cache only when they were compiled for this process's CPU target."""

import json
import os
import shutil
import subprocess
import sys
import time

import pytest

import core
from core.jit import cache_folder, relocatable, warmup
from core.jit.relocatable import PORTABLE_LEVELS, host_portable_level

CORE = os.path.dirname(core.__file__)
ROOT = os.path.dirname(CORE)

# Compiles (or loads) one small kernel and says which, and where its cache files went
CALL_A_KERNEL = r"""
import json, numba
from core.jit.cache_folder import kernel_cache_dir
from core.jit.decorators import CPU_TARGET
from core.kernels.vec import dot
assert dot((1.0, 2.0, 3.0), (4.0, 5.0, 6.0)) == 32.0
from numba.core.registry import cpu_target
print(json.dumps({"hits": sum(dot.stats.cache_hits.values()),
                  "misses": sum(dot.stats.cache_misses.values()),
                  "target": CPU_TARGET,
                  "magic": list(cpu_target.target_context.codegen().magic_tuple()),
                  "cache": str(kernel_cache_dir())}))
"""


def call_a_kernel(package_root, cache_base, **more_env):
    env = {**os.environ, "PYTHONPATH": str(package_root), "WHITTED_CACHE_DIR": str(cache_base)}
    run = subprocess.run(
        [sys.executable, "-c", CALL_A_KERNEL], cwd=package_root, env={**env, **more_env},
        capture_output=True, text=True, timeout=300,
    )  # fmt: skip
    assert run.returncode == 0, run.stderr
    return json.loads(run.stdout.splitlines()[-1])


def copy_core(to):
    # shutil.copy gives every file a new modification time, as unpacking a zip does
    ignore = shutil.ignore_patterns("__pycache__")
    shutil.copytree(CORE, to / "core", copy_function=shutil.copy, ignore=ignore)
    return to


def test_a_cache_moved_with_core_to_another_folder_loads_without_compiling(tmp_path):
    first = call_a_kernel(copy_core(tmp_path / "built_here"), tmp_path / "cache")
    assert first["misses"] == 1 and first["hits"] == 0
    shutil.copytree(tmp_path / "cache", tmp_path / "moved_cache")
    moved = call_a_kernel(copy_core(tmp_path / "installed_there"), tmp_path / "moved_cache")
    assert moved["hits"] == 1 and moved["misses"] == 0, moved
    # in the folder named by the module's place in the package, not by its absolute path
    assert list((tmp_path / "moved_cache").glob("*/core/kernels/vec.dot-*.nbi")), moved


@pytest.mark.skipif(host_portable_level() is None, reason="this CPU lacks x86-64-v3")
def test_kernels_compile_for_the_portable_level_or_the_cpu_the_user_names(tmp_path):
    level = host_portable_level()
    ours = call_a_kernel(copy_core(tmp_path / "a"), tmp_path / "cache")
    assert ours["target"] == level and ours["magic"][1:] == [level, ""], ours
    named = call_a_kernel(tmp_path / "a", tmp_path / "cache", NUMBA_CPU_NAME="generic")
    # another target's kernels are compiled anew beside the first, never run
    assert named["magic"][1:] == ["generic", ""] and named["misses"] == 1, named


@pytest.fixture
def shipped(tmp_path, monkeypatch):
    """A stand-in for the extension's kernel_cache folder, and an empty user cache."""
    monkeypatch.setenv("WHITTED_CACHE_DIR", str(tmp_path / "user_cache"))
    monkeypatch.setattr(cache_folder, "SHIPPED_KERNELS", tmp_path / "extension" / "kernel_cache")
    folder = cache_folder.shipped_kernels()
    (folder / "core" / "kernels").mkdir(parents=True)
    (folder / "core" / "kernels" / "trace.closest_hit-12.py311.nbi").write_bytes(b"index")
    (folder / "core" / "kernels" / "trace.closest_hit-12.py311.1.nbc").write_bytes(b"code" * 99)
    return folder


def test_shipped_kernels_for_this_target_are_copied_once(shipped, capsys):
    (shipped / warmup.MARKER).write_text("built\n")
    assert warmup.kernels_ready()
    user = warmup.kernel_cache_dir()
    for path in shipped.rglob("*"):
        if path.is_file():
            assert (user / path.relative_to(shipped)).read_bytes() == path.read_bytes()
    assert "copied the extension's compiled kernels" in capsys.readouterr().err
    assert not list(user.rglob("*.partial"))
    assert warmup.kernels_ready()
    assert "copied" not in capsys.readouterr().err  # once: the user's folder is complete now


def test_shipped_kernels_for_another_target_are_left_alone(shipped):
    (shipped / "warm-some-other-cpu.ok").write_text("built\n")
    assert not warmup.kernels_ready()
    assert not warmup.kernel_cache_dir().exists()


@pytest.mark.parametrize(
    "has, level",
    [
        (PORTABLE_LEVELS["x86-64-v4"], "x86-64-v4"),
        (PORTABLE_LEVELS["x86-64-v3"] | {"avx512f"}, "x86-64-v3"),  # AVX-512 in part: not v4
        (PORTABLE_LEVELS["x86-64-v3"] - {"fma"}, None),  # Sandy/Ivy Bridge: AVX without FMA
    ],
)
def test_a_cpu_gets_the_highest_level_it_has_in_full(monkeypatch, has, level):
    features = {name: name in has for name in PORTABLE_LEVELS["x86-64-v4"]}
    monkeypatch.setattr(relocatable.llvm, "get_host_cpu_features", lambda: features)
    monkeypatch.setattr(relocatable.platform, "machine", lambda: "x86_64")
    assert relocatable.host_portable_level() == level


def test_cache_folders_unused_for_a_month_are_pruned_and_no_others(tmp_path, monkeypatch):
    monkeypatch.setenv("WHITTED_CACHE_DIR", str(tmp_path))
    current = warmup.kernel_cache_dir()
    month = 86400 * cache_folder.STALE_DAYS
    folders = {
        "current": current,
        "stale": tmp_path / "whitted-0.0.9-numba-0.60.0-py311-0123456789ab",
        "in use": tmp_path / "whitted-0.1.0-numba-0.68.1-py313-0123456789ab",
        "not ours": tmp_path / "somebody-elses-cache",
    }
    for folder in folders.values():
        (folder / "core").mkdir(parents=True)
        (folder / "core" / "x.nbi").write_bytes(b"index")
    for name in ("current", "stale", "not ours"):
        os.utime(folders[name], (0, time.time() - month - 60))
    removed = cache_folder.prune_stale()
    assert removed == [folders["stale"]]
    assert [name for name, f in folders.items() if f.exists()] == ["current", "in use", "not ours"]
    # a render marks its folder used
    cache_folder.note_use()
    assert time.time() - current.stat().st_mtime < 60


# A mesh traversal (the eight-wide box test, the four-wide triangle test) compiled anew for a
# level, and the AVX-512 marks in its machine code: zmm registers, mask registers, the
# EVEX-only xmm/ymm16-31, broadcasts, vpternlog. Compiled anew because machine code loaded
# from a cache has no assembly to read; what it calls may load.
COUNT_AVX512 = r"""
import re
import numba
import numpy as np
from core import Mesh, RenderSettings, Scene, TriangleMesh
from core.kernels.mesh_trace import mesh_line_crossings
from core.compile import compile_scene
from tests.support.meshes import icosphere
v, t = icosphere(2)
scene = Scene(shapes=[Mesh(mesh=TriangleMesh(v, t))])
g = compile_scene(scene, RenderSettings(8, 8, pixel_samples=1)).packed.geometry
fresh = numba.njit(nogil=True, error_model="numpy")(mesh_line_crossings.py_func)
fresh(g.node_boxes, g.node_links, g.tri_corners, g.mesh_root[0], (0.0, 0.0, 0.0),
      (0.0, 0.0, 1.0), np.empty((64, 3)), np.empty((64, 2), np.int32), np.empty(256, np.int32))
asm = "".join(fresh.inspect_asm().values())
marks = r"%zmm\d+|%k[1-7]\b|%[xy]mm(?:1[6-9]|2\d|3[01])\b|\{1to\d+\}|vpternlog"
print(len(re.findall(marks, asm)), len(re.findall(r"%ymm\d+", asm)))
"""


@pytest.mark.skipif(host_portable_level() != "x86-64-v4", reason="this CPU cannot run v4 code")
def test_kernels_for_the_v3_level_hold_no_avx512_instruction():
    """What the extension ships for x86-64-v3 runs on a CPU without AVX-512, though it was
    compiled on one with it: the same kernel compiled for v4 shows the marks the check looks
    for."""
    counts = {}
    for level in PORTABLE_LEVELS:
        env = {**os.environ, "NUMBA_CPU_NAME": level, "NUMBA_CPU_FEATURES": ""}
        run = subprocess.run([sys.executable, "-c", COUNT_AVX512], cwd=ROOT, env=env,
                             capture_output=True, text=True, timeout=600)  # fmt: skip
        assert run.returncode == 0, run.stderr
        avx512, ymm = map(int, run.stdout.split()[-2:])
        assert ymm > 100, (level, run.stdout)  # real vector code was read
        counts[level] = avx512
    assert counts["x86-64-v3"] == 0 and counts["x86-64-v4"] > 100, counts
