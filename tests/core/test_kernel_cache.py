"""A damaged kernel cache heals itself (core.jit.cache_folder): in fresh processes sharing one
cache folder, a kernel is cached, its files are cut short, zeroed or garbled, and the next
process must say so in one line, rebuild the cache and return the right answer; the one after
must load the rebuilt cache cleanly."""

import os
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from PIL import Image

from core.jit.cache_folder import load_or_rebuild

ROOT = Path(__file__).resolve().parents[2]
CHILD = (
    "from core.jit.cache_folder import load_or_rebuild\n"
    "from tests.support.cache_probe import doubled\n"
    "value, rebuilt = load_or_rebuild(lambda: doubled(21.0))\n"
    "print(value, rebuilt)\n"
)


def run_child(cache: Path) -> subprocess.CompletedProcess:
    env = {**os.environ, "WHITTED_CACHE_DIR": str(cache)}
    return subprocess.run(
        [sys.executable, "-c", CHILD], cwd=ROOT, env=env, capture_output=True, text=True
    )


def damage(path: Path, how: str) -> None:
    data = path.read_bytes()
    if how == "truncated":
        path.write_bytes(data[: len(data) // 2])
    elif how == "zeroed":
        path.write_bytes(bytes(len(data)))
    else:
        path.write_bytes((b"garbled!" * len(data))[: len(data)])


@pytest.mark.parametrize("how", ["truncated", "zeroed", "garbled"])
@pytest.mark.parametrize("files", ["*.nbi", "*.nbc"])
def test_a_damaged_cache_is_removed_and_rebuilt(tmp_path, how, files):
    first = run_child(tmp_path)
    assert first.returncode == 0, first.stderr
    assert first.stdout.split() == ["42.0", "False"]
    cached = sorted(tmp_path.rglob(files))
    assert cached, f"no {files} cache files were written"
    for path in cached:
        damage(path, how)

    healed = run_child(tmp_path)
    assert healed.returncode == 0, healed.stderr
    assert healed.stdout.split() == ["42.0", "True"]
    said = [line for line in healed.stderr.splitlines() if "was damaged" in line]
    assert len(said) == 1, healed.stderr
    assert said[0].startswith("Whitted: the kernel cache's copy of cache_probe.doubled was ")
    assert "compiling it again" in said[0]
    assert sorted(tmp_path.rglob(files)), "the cache was not written again"

    after = run_child(tmp_path)
    assert after.returncode == 0, after.stderr
    assert after.stdout.split() == ["42.0", "False"]
    assert "damaged" not in after.stderr


def test_errors_that_are_not_the_cache_are_not_swallowed():
    with pytest.raises(ZeroDivisionError):
        load_or_rebuild(lambda: 1 / 0)


def test_an_error_while_writing_the_cache_is_not_taken_for_damage(monkeypatch, tmp_path):
    """A full disk while numba saves a kernel is not a damaged cache: compiling again would
    only meet it again, so it is raised as it is, after one compile."""
    from numba.core import caching

    from tests.support.cache_probe import doubled

    assert doubled(1.0) == 2.0  # compiled or loaded before the disk fills

    def disk_full(self, name, data):
        raise OSError(28, "No space left on device")

    monkeypatch.setattr(caching.IndexDataCacheFile, "_save_data", disk_full)
    # Were it taken for damage, the folder removed would be this one, not the shared cache
    monkeypatch.setenv("WHITTED_CACHE_DIR", str(tmp_path))
    compiles = []

    def compile_again():
        compiles.append(1)
        doubled.recompile()  # compiles, then saves to the cache

    with pytest.raises(OSError, match="No space left"):
        load_or_rebuild(compile_again)
    assert len(compiles) == 1


SCENES = ROOT / "tests" / "cs488_scenes"


def render_script(cache: Path, folder: Path, output: Path) -> subprocess.CompletedProcess:
    env = {**os.environ, "WHITTED_CACHE_DIR": str(cache), "PYTHONPATH": str(ROOT)}
    return subprocess.run(
        [sys.executable, "-m", "core", "render", "every_command.lua", "-o", str(output)],
        cwd=folder, env=env, capture_output=True, text=True, timeout=900,
    )  # fmt: skip


@pytest.fixture(scope="module")
def rendered_with_the_shared_cache(tmp_path_factory):
    """The report's every-command scene (meshes, CSG, a texture, lights: every compile-step
    kernel) rendered with the shared cache, warmed by it if need be: (folder, picture)."""
    folder = tmp_path_factory.mktemp("scene")
    for path in SCENES.iterdir():
        shutil.copy(path, folder / path.name)
    result = render_script(Path(os.environ["WHITTED_CACHE_DIR"]), folder, folder / "clean.png")
    assert result.returncode == 0, result.stderr
    return folder, np.asarray(Image.open(folder / "clean.png"))


@pytest.mark.parametrize("how", ["empty", "truncated", "garbled"])
@pytest.mark.parametrize("files", ["*.nbi", "*.nbc"])
def test_every_cached_function_heals_the_compile_steps_included(
    rendered_with_the_shared_cache, tmp_path, how, files
):
    """Every kernel's files but the render kernel's are damaged (its 3-minute compile is the
    probe's test above): the compile step's kernels (the BVH builder, which the healing of
    the render kernel alone missed: `EOFError: Ran out of input` from every render); the
    kernels they call have no files of their own, their code being inside their callers'
    (core.jit.deferred). The render must still come out right, saying so once, and the next
    load cleanly."""
    from core.jit.cache_folder import kernel_cache_dir

    folder, clean = rendered_with_the_shared_cache
    copy = tmp_path / "cache" / kernel_cache_dir().name
    shutil.copytree(kernel_cache_dir(), copy)
    damaged = [p for p in copy.rglob(files) if not p.name.startswith("render_tile.render_tile-")]
    assert any(p.name.startswith("bvh_build.build_bvh-") for p in damaged), damaged
    assert len(damaged) >= 10, damaged
    for path in damaged:
        if how == "empty":
            path.write_bytes(b"")
        else:
            damage(path, how)
    healed = render_script(tmp_path / "cache", folder, tmp_path / "healed.png")
    assert healed.returncode == 0, healed.stderr
    said = [line for line in healed.stderr.splitlines() if "was damaged" in line]
    assert len(said) == 1, healed.stderr
    assert said[0].startswith("Whitted: the kernel cache's copy of ")
    assert np.array_equal(np.asarray(Image.open(tmp_path / "healed.png")), clean)
    again = render_script(tmp_path / "cache", folder, tmp_path / "again.png")
    assert again.returncode == 0 and "damaged" not in again.stderr, again.stderr
