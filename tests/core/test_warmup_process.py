"""The warm-up process as the add-on watches it, with stand-in children (shell scripts that
print what `python -m core.jit.warmup` prints, or fail): progress lines become its
status, a cancelled wait returns at once while the child goes on, a failed or foreign child
is reported as failed with its last words. The real warm-up's compile is tested in
test_kernel_signature."""

import os
import shutil
import stat
import subprocess
import sys
import time
from pathlib import Path

import pytest

import core
from core.jit import warmup as kernel_warmup
from core.jit.cache_folder import kernel_cache_dir
from core.jit.child_process import PROGRAM, program_arguments
from core.jit.warmup_process import WarmupProcess

OWN_CORE = kernel_warmup.own_core()
ROOT = Path(core.__file__).resolve().parent.parent


def fake_python(tmp_path, body: str) -> str:
    script = tmp_path / "python"
    script.write_text("#!/bin/sh\n" + body)
    script.chmod(script.stat().st_mode | stat.S_IXUSR)
    return [str(script)]


@pytest.fixture(autouse=True)
def empty_cache(tmp_path, monkeypatch):
    monkeypatch.setenv("WHITTED_CACHE_DIR", str(tmp_path / "cache"))


def wait_until_done(warmup, seconds=20.0):
    deadline = time.monotonic() + seconds
    while warmup.status().state == "running" and time.monotonic() < deadline:
        time.sleep(0.02)
    return warmup.status()


def test_progress_lines_become_the_status_and_a_clean_exit_is_ready(tmp_path):
    python = fake_python(
        tmp_path,
        f'echo "Whitted: core {OWN_CORE}"\n'
        'echo "Whitted: compiling kernels: 1 of 2 (scene packing)"\n'
        "sleep 0.3\n"
        'echo "Whitted: compiling kernels: 2 of 2 (render kernel)"\n'
        "sleep 0.3\n",
    )
    warmup = WarmupProcess(python)
    warmup.start()
    seen = []
    status = warmup.wait(lambda: False, lambda s: seen.append(s.text), poll_s=0.01)
    assert status.state == "ready"
    # each line once (the wait calls again each second, for a clock)
    steps = [text for text in dict.fromkeys(seen) if text != "compiling kernels: starting"]
    assert steps == ["compiling kernels: 1 of 2 (scene packing)",
                     "compiling kernels: 2 of 2 (render kernel)"]  # fmt: skip


def test_the_ready_line_is_ready_while_the_child_is_still_exiting(tmp_path):
    """The child writes its marker, then prints the ready line: a render need not wait for
    what follows (pruning, the interpreter's exit), here a child that lingers."""
    gone = tmp_path / "gone"
    python = fake_python(
        tmp_path,
        f'echo "Whitted: core {OWN_CORE}"\n'
        'echo "Whitted: compiling kernels: 1 of 1 (render kernel)"\n'
        'echo "Whitted: kernels ready in 1.0 s (render kernel 1.0 s)"\n'
        f"sleep 30\ntouch {gone}\n",
    )
    warmup = WarmupProcess(python)
    warmup.start()
    status = warmup.wait(lambda: False, lambda s: None, poll_s=0.01)
    try:
        assert status.state == "ready" and status.text.startswith("kernels ready")
        assert warmup._process.poll() is None and not gone.exists()  # still there
    finally:
        warmup._process.kill()
        warmup._process.wait()


def test_a_cancelled_wait_returns_at_once_and_the_child_goes_on(tmp_path):
    done = tmp_path / "done"
    python = fake_python(
        tmp_path,
        f'echo "Whitted: compiling kernels: 1 of 1 (render kernel)"\nsleep 1.5\ntouch {done}\n',
    )
    warmup = WarmupProcess(python)
    warmup.start()
    start = time.monotonic()
    status = warmup.wait(lambda: True, lambda s: None, poll_s=0.01)
    assert status.state == "running"
    assert time.monotonic() - start < 0.5
    assert wait_until_done(warmup).state == "ready"
    assert done.exists()


def test_a_failing_child_is_reported_with_its_last_words_and_not_retried(tmp_path):
    python = fake_python(tmp_path, 'echo "ModuleNotFoundError: No module named numba"\nexit 1\n')
    warmup = WarmupProcess(python)
    warmup.start()
    status = wait_until_done(warmup)
    assert status.state == "failed"
    assert "status 1" in status.text and "No module named numba" in status.text
    warmup.start()
    assert warmup.status().state == "failed"


def test_a_child_that_compiled_another_core_is_a_failure(tmp_path):
    python = fake_python(tmp_path, 'echo "Whitted: core /somewhere/else/core"\n')
    warmup = WarmupProcess(python)
    warmup.start()
    status = wait_until_done(warmup)
    assert status.state == "failed" and "/somewhere/else/core" in status.text


def test_an_interpreter_that_cannot_start_is_a_failure(tmp_path):
    warmup = WarmupProcess([str(tmp_path / "no-such-python")])
    warmup.start()
    status = warmup.status()
    assert status.state == "failed" and "could not start" in status.text


def test_no_child_starts_when_the_cache_is_complete(tmp_path):
    marker = kernel_warmup.marker_path()
    marker.parent.mkdir(parents=True)
    marker.write_text("done\n")
    started = tmp_path / "started"
    warmup = WarmupProcess(fake_python(tmp_path, f"touch {started}\n"))
    warmup.start()
    assert warmup.status().state == "ready"
    time.sleep(0.2)
    assert not started.exists()
    assert os.environ["WHITTED_CACHE_DIR"] in str(marker)


def test_a_second_warmup_waits_for_the_first_and_then_compiles_nothing():
    """Two warm-ups on one cache (two Blenders started at once): the second says it waits,
    and once the first is done finds the cache complete. Here the test holds the lock as
    the first process would, and writes the first's marker before letting go."""
    fcntl = pytest.importorskip("fcntl")
    folder = kernel_warmup.kernel_cache_dir()
    folder.mkdir(parents=True)
    with open(folder / kernel_warmup.LOCK, "w") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)
        second = subprocess.Popen(
            [sys.executable, "-m", "core.jit.warmup"], cwd=ROOT, env=dict(os.environ),
            stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
        )  # fmt: skip
        # what it imported, where its cache is, and then that it waits
        first_lines = [second.stdout.readline() for _ in range(3)]
        assert "waiting for another process" in first_lines[2], first_lines
        kernel_warmup.marker_path().write_text("the first's warm-up\n")
    out, _ = second.communicate(timeout=120)
    assert second.returncode == 0, out
    assert "the cache is complete" in out and "1 of" not in out, out


def test_the_child_imports_core_under_the_parents_name_without_running_its_parents(tmp_path):
    """In Blender `core` is an add-on's subpackage, and numba's cache records that name: the
    child must import it so too, from the same folder, without the add-on's __init__ (which
    needs Blender) running. Here that __init__ raises, and the cache is complete, so the
    child only says what it imported."""
    name = "bl_ext.some_repo.whitted.core"
    staged = tmp_path.joinpath(*name.split("."))
    shutil.copytree(ROOT / "core", staged, ignore=shutil.ignore_patterns("__pycache__"))
    (staged.parent / "__init__.py").write_text("raise ImportError('the add-on ran')\n")
    folder = kernel_cache_dir()  # in this test's own cache folder, whatever the name
    folder.mkdir(parents=True)
    (folder / kernel_warmup.MARKER).write_text("compiled\n")
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
    run = subprocess.run(
        [sys.executable, "-c", PROGRAM, *program_arguments("jit.warmup", name, staged)],
        cwd=tmp_path, env=env, capture_output=True, text=True, timeout=120,
    )  # fmt: skip
    assert run.returncode == 0, run.stdout + run.stderr
    assert f"Whitted: core {name} at {staged.resolve()}" in run.stdout
    assert "the cache is complete" in run.stdout


def test_a_variants_warmup_serves_the_scenes_that_leave_out_as_much_or_more():
    """The marker of a variant's warm-up (core.jit.variants) says its kernels are ready for
    a render that needs fewer features, not for one that needs a feature it left out; the
    full kernel's serves every render."""
    without = frozenset({"nodes", "caustics"})
    assert not kernel_warmup.kernels_ready(without)
    kernel_warmup.marker_path(without).parent.mkdir(parents=True)
    kernel_warmup.marker_path(without).write_text("done\n")
    assert kernel_warmup.kernels_ready(without)
    assert kernel_warmup.kernels_ready(without | {"passes"})
    assert not kernel_warmup.kernels_ready(frozenset({"nodes"}))  # it needs caustics
    assert not kernel_warmup.kernels_ready()
    kernel_warmup.marker_path().write_text("done\n")
    assert kernel_warmup.kernels_ready(frozenset({"nodes"})) and kernel_warmup.kernels_ready()


def test_a_variants_warmup_child_is_told_what_to_leave_out(tmp_path, monkeypatch):
    """The child's command line names the variant (`--without TAG`), and its steps leave
    the photon kernels out when the variant holds no caustics."""
    from core.jit import child_process
    from core.jit.variants import tag

    without = frozenset({"caustics", "environment"})
    said = tmp_path / "arguments"
    launcher = fake_python(tmp_path, f'echo "$@" > {said}\necho "Whitted: core {OWN_CORE}"\n')
    monkeypatch.setattr(child_process, "_launcher", launcher)
    warmup = WarmupProcess(None, without)
    warmup.start()
    assert wait_until_done(warmup).state == "ready"
    assert said.read_text().split()[-2:] == ["--without", tag(without)]
    steps = [label for label, _ in kernel_warmup.warmup_steps(without)]
    assert "caustic photons" not in steps and steps[-1] == "render kernel"
    assert "caustic photons" in [label for label, _ in kernel_warmup.warmup_steps()]


def test_the_packing_kernels_compile_beside_and_here_if_that_fails(tmp_path, monkeypatch):
    """A warm-up starts the packing's and photon pass's kernels' compile in a process of its
    own at once (`--beside`, by the launcher it was started with, for the same variant) and
    waits for it last; if that process fails, it compiles them itself."""
    from core.jit import child_process
    from core.jit.variants import tag

    said = tmp_path / "arguments"
    launcher = fake_python(tmp_path, f'echo "$@" > {said}\necho "it broke"\nexit 3\n')
    monkeypatch.setattr(child_process, "_launcher", launcher)
    compiled_here = []
    monkeypatch.setattr(kernel_warmup, "warm_photon_kernels", compiled_here.append)
    monkeypatch.setattr(kernel_warmup, "_packed_warmup_scene", lambda without: "packed")
    without = frozenset({"nodes"})
    kernel_warmup.Beside(without).finish()
    assert said.read_text().split()[-3:] == [kernel_warmup.BESIDE, "--without", tag(without)]
    assert compiled_here == ["packed"]
    compiled_here.clear()
    kernel_warmup.compile_beside(frozenset({"caustics"}))
    assert compiled_here == []  # no photon kernels for a variant without caustics
    # the launcher travels to the children's children
    env = child_process.environment()
    assert env[child_process.LAUNCHER_VARIABLE].startswith("[")


def test_the_progress_bar_follows_either_order_of_the_steps():
    beside = ["nearest hits", "shadow rays", "render kernel", "scene packing and caustic photons"]
    serial = ["scene packing", "nearest hits", "shadow rays", "render kernel", "caustic photons"]
    for steps in (beside, serial, beside[:3] + ["scene packing"], serial[:4]):
        fractions = []
        for k, label in enumerate(steps, 1):
            line = kernel_warmup.progress_line(k, len(steps), label)
            fractions += [kernel_warmup.progress_fraction(line, s) for s in (0.0, 2.0, 1e6)]
        assert fractions == sorted(fractions) and fractions[0] == 0.0, (steps, fractions)
        assert 0.8 < fractions[-1] <= 1.0, (steps, fractions)


def test_a_serial_warmup_compiles_the_photon_kernels_in_turn(monkeypatch):
    monkeypatch.setenv(kernel_warmup.SERIAL_SWITCH, "1")
    assert not kernel_warmup._may_compile_beside()
    monkeypatch.setenv(kernel_warmup.SERIAL_SWITCH, "0")
    assert kernel_warmup._may_compile_beside() == ((os.cpu_count() or 1) > 1)
