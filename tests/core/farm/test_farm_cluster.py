"""The farm on a real Dask LocalCluster of two worker processes on this machine, running the
real `blender -b` (Debian's 3.4) and the CS488 command line: stitched borders equal the
single-machine render bit for bit, a frame range renders every frame once, a worker killed
mid-job changes nothing, a failing scene fails the job with the worker's message and writes
nothing, an unreachable scheduler and Ctrl-C are reported cleanly."""

import os
import re
import shutil
import signal
import subprocess
import sys
import threading

import numpy as np
import pytest
from PIL import Image

from core.farm import client as farm_client
from core.farm.jobs import FarmError
from core.farm.worker import SUMMARY
from tests.support import ROOT
from tests.support.blender34 import blender_34
from tests.support.hostile import processes_with

distributed = pytest.importorskip("distributed")

SAMPLE = ROOT / "sample_blends" / "spheres.blend"
LUA = ROOT / "tests" / "cs488_scenes" / "every_command.lua"
SITE = ROOT / ".venv" / "lib" / "python3.11" / "site-packages"
BLENDER = ("blender", "--python-use-system-env")


@pytest.fixture(scope="module")
def cluster():
    """Two single-threaded worker processes, with Blender's environment as `make render`
    sets it (the add-on from BLENDER_USER_SCRIPTS, numba from the project's venv)."""
    if shutil.which("blender") is None:
        pytest.skip("no blender on PATH: run `make setup`")
    saved = dict(os.environ)
    os.environ["PYTHONPATH"] = f"{ROOT}{os.pathsep}{SITE}"
    os.environ.setdefault("BLENDER_USER_SCRIPTS", str(ROOT / ".build" / "blender_scripts"))
    local = distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                     dashboard_address=None)  # fmt: skip
    yield local
    local.close()
    os.environ.clear()
    os.environ.update(saved)


def job(cluster, scene, output, **changes):
    base = dict(scene=scene, output=str(output), scheduler=cluster.scheduler_address,
                blender=BLENDER)  # fmt: skip
    return farm_client.Job(**{**base, **changes})


@pytest.fixture(scope="module")
def single_run(tmp_path_factory):
    """The sample rendered whole by one `blender -b`, as a farm-less user does: (its image,
    its log)."""
    folder = tmp_path_factory.mktemp("single")
    run = blender_34(str(SAMPLE), "--addons", "whitted", "-E", "WHITTED",
                     "-o", f"{folder}/single_####", "-F", "PNG", "-f", "1")  # fmt: skip
    assert run.returncode == 0, run.stdout[-2000:]
    return np.asarray(Image.open(folder / "single_0001.png")), run.stdout


@pytest.fixture(scope="module")
def single_render(single_run):
    return single_run[0]


def pixels(path):
    return np.asarray(Image.open(path))


def test_a_4x4_split_stitches_to_the_single_render_bit_for_bit(cluster, single_run, tmp_path):
    lines = []
    report = farm_client.run_job(job(cluster, SAMPLE, tmp_path / "out_####.png", split=(4, 4)),
                                 say=lines.append)  # fmt: skip
    assert report.tasks == 16 and report.written == [tmp_path / "out_0001.png"]
    np.testing.assert_array_equal(pixels(tmp_path / "out_0001.png"), single_run[0])
    # Every pixel's rays are the same wherever it renders: the borders' counts, each to the
    # thousand its summary prints, add up to the whole frame's
    (whole,) = {float(m["rays"]) * 1e6 for m in SUMMARY.finditer(single_run[1])}
    whole_rounding = 500 if whole < 1e6 else 50_000  # 0.137 M rays; 2.5 M rays
    assert abs(report.rays - whole) <= 16 * 500 + whole_rounding, (report.rays, whole)
    assert any(line.startswith("Farm: 16/16 tasks") and "s left" in line for line in lines)
    assert f"Saved: '{tmp_path / 'out_0001.png'}'" in lines


def test_a_lua_scene_splits_and_stitches_too(cluster, tmp_path):
    scenes = tmp_path / "scenes"
    shutil.copytree(LUA.parent, scenes)
    farm_client.run_job(job(cluster, scenes / LUA.name, tmp_path / "farm.png", split=(4, 4)),
                        say=lambda line: None)  # fmt: skip
    single = [sys.executable, "-m", "core", "render", scenes / LUA.name, "-o",
              tmp_path / "single.png"]  # fmt: skip
    subprocess.run(single, check=True, capture_output=True, cwd=ROOT)
    np.testing.assert_array_equal(pixels(tmp_path / "farm.png"), pixels(tmp_path / "single.png"))


def test_a_caustic_scene_splits_with_the_same_photons_on_every_worker(cluster, tmp_path):
    """Every worker traces the photon pass for its border from the same seed: the same
    photons, so the stitched caustic has no seams (bit for bit the single render's)."""
    from tests.core.cs488.test_render_options import CAMERA, MIRROR_SCENE

    script = tmp_path / "mirror.lua"
    script.write_text(MIRROR_SCENE + f"gr.render(root, 'out.png', 48, 48, {CAMERA}, "
                      "{caustics = 'reflective', photons = 30000})\n")  # fmt: skip
    farm_client.run_job(job(cluster, script, tmp_path / "farm.png", split=(3, 2)),
                        say=lambda line: None)  # fmt: skip
    single = [sys.executable, "-m", "core", "render", script, "-o", tmp_path / "single.png"]
    run = subprocess.run(single, check=True, capture_output=True, text=True, cwd=ROOT)
    assert "photons traced" in run.stdout  # the pass ran
    np.testing.assert_array_equal(pixels(tmp_path / "farm.png"), pixels(tmp_path / "single.png"))


def test_a_frame_range_renders_every_frame_once(cluster, single_render, tmp_path):
    report = farm_client.run_job(
        job(cluster, SAMPLE, tmp_path / "frame_####.png", frames=(1, 2, 3), chunk=2),
        say=lambda line: None,
    )
    assert report.tasks == 2  # frames 1-2, then 3
    names = sorted(p.name for p in tmp_path.iterdir())
    assert names == ["frame_0001.png", "frame_0002.png", "frame_0003.png"]
    for name in names:  # the sample does not move: every frame is the single render
        np.testing.assert_array_equal(pixels(tmp_path / name), single_render)


def test_a_worker_killed_mid_job_changes_nothing(cluster, single_render, tmp_path):
    with distributed.Client(cluster.scheduler_address) as client:
        pids = list(client.run(os.getpid).values())
    killed = threading.Event()

    def say(line):
        if line.startswith("Farm: 2/") and not killed.is_set():
            os.kill(pids[0], signal.SIGKILL)  # a worker process, and the render it runs
            killed.set()

    report = farm_client.run_job(job(cluster, SAMPLE, tmp_path / "out_####.png", split=(3, 3)),
                                 say=say)  # fmt: skip
    assert killed.is_set() and report.tasks == 9
    np.testing.assert_array_equal(pixels(tmp_path / "out_0001.png"), single_render)


def test_a_warm_blender_opens_the_scene_again_when_its_file_changes(cluster, tmp_path):
    scene = tmp_path / "scene.blend"
    shutil.copy(SAMPLE, scene)
    farm_client.run_job(job(cluster, scene, tmp_path / "before_####.png", split=(2, 1)),
                        say=lambda line: None)  # fmt: skip
    move = ("import bpy; bpy.data.objects['Blue'].location.x += 0.5; "
            f"bpy.ops.wm.save_as_mainfile(filepath={str(scene)!r})")  # fmt: skip
    assert blender_34(str(scene), "--python-expr", move).returncode == 0
    farm_client.run_job(job(cluster, scene, tmp_path / "after_####.png", split=(2, 1)),
                        say=lambda line: None)  # fmt: skip
    run = blender_34(str(scene), "--addons", "whitted", "-E", "WHITTED",
                     "-o", f"{tmp_path}/single_####", "-F", "PNG", "-f", "1")  # fmt: skip
    assert run.returncode == 0, run.stdout[-2000:]
    after = pixels(tmp_path / "after_0001.png")
    np.testing.assert_array_equal(after, pixels(tmp_path / "single_0001.png"))
    assert not np.array_equal(after, pixels(tmp_path / "before_0001.png"))


def test_a_blender_per_task_gives_the_same_image(cluster, single_render, tmp_path):
    report = farm_client.run_job(
        job(cluster, SAMPLE, tmp_path / "out_####.png", split=(2, 2), fresh_blender=True),
        say=lambda line: None,
    )
    assert report.tasks == 4
    np.testing.assert_array_equal(pixels(tmp_path / "out_0001.png"), single_render)


def test_a_blender_that_cannot_start_fails_the_job_clearly(cluster, tmp_path):
    with pytest.raises(FarmError) as error:
        farm_client.run_job(job(cluster, SAMPLE, tmp_path / "out_####.png", frames=(1,),
                                blender=("no-such-blender",)), say=lambda line: None)  # fmt: skip
    assert "cannot run 'no-such-blender'" in str(error.value)
    assert "frame 1 failed on worker tcp://" in str(error.value)


def test_a_failing_scene_fails_the_job_with_the_workers_message(cluster, tmp_path):
    broken = tmp_path / "broken.blend"
    spoil = ("import bpy; bpy.data.objects['Blue'].scale = (0, 1, 1); "
             f"bpy.ops.wm.save_as_mainfile(filepath={str(broken)!r})")  # fmt: skip
    assert blender_34(str(SAMPLE), "--python-expr", spoil).returncode == 0
    (tmp_path / "tmp").mkdir()
    with pytest.raises(FarmError) as error:
        farm_client.run_job(job(cluster, broken, tmp_path / "out_####.png", split=(2, 1)),
                            say=lambda line: None)  # fmt: skip
    message = str(error.value)
    assert re.search(
        r"border \d of 2 \(column \d, row 1 from the top\) of frame 1 failed on "
        r"worker tcp://",
        message,
    )
    assert "sphere 'Blue'" in message and "non-zero scale" in message
    assert message.count("non-zero scale") == 1  # Blender's log repeats it: said once
    assert not list(tmp_path.glob("out_*"))
    # From the command line, on a cluster of its own: the error alone, not first as Dask's
    # record of a failed task in the workers' log
    run = subprocess.run(
        [sys.executable, "-m", "core", "farm", str(broken), "-o", str(tmp_path / "out_####.png"),
         "--scheduler", "local", "--workers", "1", "--blender", " ".join(BLENDER)],
        capture_output=True, text=True, cwd=ROOT, timeout=300,
        env={**os.environ, "TMPDIR": str(tmp_path / "tmp")},
    )  # fmt: skip
    assert run.returncode == 1
    assert "error: frame 1 failed on worker" in run.stderr and "non-zero scale" in run.stderr
    assert "Compute Failed" not in run.stderr and "Traceback" not in run.stderr
    assert not list(tmp_path.glob("out_*"))
    assert list((tmp_path / "tmp").iterdir()) == []  # a failed job leaves nothing there


def _tiny_blend(tmp_path):
    """The sample scene at 4 x 4 pixels."""
    tiny = tmp_path / "tiny.blend"
    shrink = ("import bpy; r = bpy.context.scene.render; r.resolution_percentage = 100; "
              "r.resolution_x, r.resolution_y = 4, 4; "
              f"bpy.ops.wm.save_as_mainfile(filepath={str(tiny)!r})")  # fmt: skip
    assert blender_34(str(SAMPLE), "--python-expr", shrink).returncode == 0
    return tiny


@pytest.mark.parametrize("fellows", ["stop in time", "outlast the wait"])
def test_a_split_finer_than_the_frames_pixels_is_a_clear_error(cluster, tmp_path, monkeypatch,
                                                               fellows):  # fmt: skip
    """One task's error ends the job, the others cancelled: whether they stop within the
    client's wait or not (still starting, or compiling kernels on a cold cache: Dask's
    TimeoutError once took the error's place, seen in a fresh clone's run), the user reads
    the error."""
    if fellows == "outlast the wait":
        import distributed

        def outlasted(futures, timeout=None, **_):
            raise TimeoutError

        monkeypatch.setattr(distributed, "wait", outlasted)
    tiny = _tiny_blend(tmp_path)
    with pytest.raises(FarmError) as error:
        farm_client.run_job(job(cluster, tiny, tmp_path / "out_####.png", frames=(1,),
                                split=(5, 1)), say=lambda line: None)  # fmt: skip
    assert "--split 5x1: the frame is only 4 x 4 pixels; split it into fewer parts" in str(
        error.value
    )
    assert not list(tmp_path.glob("out_*"))


def test_frames_of_a_lua_script_beyond_its_one_image_are_refused(cluster, tmp_path):
    with pytest.raises(FarmError) as error:
        farm_client.run_job(job(cluster, LUA, tmp_path / "out_####.png", frames=(1, 2, 3)),
                            say=lambda line: None)  # fmt: skip
    assert "--frames: every_command.lua is a CS488 script, one image (frame 1)" in str(error.value)
    assert not list(tmp_path.glob("out_*"))


def test_an_unreachable_scheduler_is_a_clear_error(tmp_path):
    run = subprocess.run(
        [sys.executable, "-m", "core", "farm", str(SAMPLE), "-o", str(tmp_path / "x.png"),
         "--scheduler", "tcp://127.0.0.1:9"],
        capture_output=True, text=True, cwd=ROOT, timeout=120,
    )  # fmt: skip
    assert run.returncode == 1
    assert "--scheduler tcp://127.0.0.1:9: cannot reach a Dask scheduler there" in run.stderr
    assert "Traceback" not in run.stderr


def test_ctrl_c_cancels_every_task_and_writes_nothing(tmp_path):
    mark = f"WHITTED_TEST_FARM={tmp_path.name}"
    (tmp_path / "tmp").mkdir()  # the job's $TMPDIR: empty again once it is cancelled
    env = dict(os.environ, PYTHONPATH=f"{ROOT}{os.pathsep}{SITE}", WHITTED_TEST_FARM=tmp_path.name,
               TMPDIR=str(tmp_path / "tmp"))  # fmt: skip
    env.setdefault("BLENDER_USER_SCRIPTS", str(ROOT / ".build" / "blender_scripts"))
    farm = subprocess.Popen(
        [sys.executable, "-m", "core", "farm", str(SAMPLE), "--split", "4x4", "--workers", "2",
         "--blender", " ".join(BLENDER), "-o", str(tmp_path / "out_####.png")],
        cwd=ROOT, env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
    )  # fmt: skip
    for line in farm.stdout:
        if line.startswith("Farm: 1/16"):
            break
    farm.send_signal(signal.SIGINT)
    _, stderr = farm.communicate(timeout=120)
    assert farm.returncode == 130, stderr
    assert "every task cancelled" in stderr and "Traceback" not in stderr
    assert not list(tmp_path.glob("out_*"))
    assert processes_with(mark) == []  # no worker, no Blender left running
    assert list((tmp_path / "tmp").iterdir()) == []  # no blender_XXXXXX, no dask-scratch-space
