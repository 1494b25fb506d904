"""The farm command's input, hostile cases, run as a user runs it (`python -m core farm`):
each refused at once with a message in the option's terms and a non-zero exit, never a wait
with no workers, a quadratic parse, a list of billions of frames in memory or a traceback;
and no job, finished, failed or cancelled, leaves a file in $TMPDIR (Blender's
blender_XXXXXX folders, Dask's dask-scratch-space)."""

import os
import subprocess
import sys
import time

import pytest

from core.farm.jobs import LAST_FRAME, FarmError, Plan, parse_frames
from tests.support import ROOT

SAMPLE = ROOT / "sample_blends" / "spheres.blend"
SITE = ROOT / ".venv" / "lib" / "python3.11" / "site-packages"
BLENDER = "blender --python-use-system-env"
BAD_SYNTAX = "r = gr.node('r'\n"

# (what the case is, the arguments after the scene, the exit status, what stderr must say)
CASES = [
    ("workers -1", ["--workers", "-1"], 2,
     "argument --workers: got '-1'; give a whole number from 0 to 256"),
    ("workers a billion", ["--workers", "1000000000"], 2, "from 0 to 256"),
    ("workers not a number", ["--workers", "two"], 2, "argument --workers: got 'two'"),
    ("workers 1e3", ["--workers", "1e3"], 2, "argument --workers: got '1e3'"),
    ("threads -5", ["--threads", "-5"], 2, "argument --threads: got '-5'"),
    ("threads 2^64", ["--threads", str(2**64)], 2, "from 0 to 1,024"),
    ("chunk 0", ["--chunk", "0"], 2, "argument --chunk: got '0'; give a whole number from 1"),
    ("chunk of 2^40", ["--chunk", str(2**40)], 2, "argument --chunk"),
    ("frames 1-3000000000", ["--frames", "1-3000000000"], 2,
     f"Blender's frames run from {-LAST_FRAME} to {LAST_FRAME}"),
    ("frames of 40 digits", ["--frames", "1" * 40], 2, "give frames as 1-250"),
    ("frames backwards", ["--frames", "9-2"], 2, "9-2 runs backwards"),
    ("frames empty", ["--frames", ""], 2, "give frames as"),
    ("split 0x4", ["--split", "0x4"], 2, "give columns x rows"),
    ("split of 10^10 borders", ["--split", "100000x100000"], 2,
     "10,000,000,000 borders a frame; at most 65,536"),
    # parsed in linear time: refused for the missing scene, at once, after the parse
    ("frames overlapping", ["--frames", "1-300000,1-300000"], 1, "no such scene file"),
    ("frames listed 10,000 times", ["--frames", ",".join(["1-1000000"] * 10_000)], 1,
     "no such scene file"),
]  # fmt: skip


def farm(*args, tmp=None, timeout=120):
    env = {**os.environ, "PYTHONPATH": f"{ROOT}{os.pathsep}{SITE}"}
    env.setdefault("BLENDER_USER_SCRIPTS", str(ROOT / ".build" / "blender_scripts"))
    if tmp is not None:
        env["TMPDIR"] = str(tmp)
    return subprocess.run([sys.executable, "-m", "core", "farm", *map(str, args)], env=env,
                          capture_output=True, text=True, cwd=ROOT, timeout=timeout)  # fmt: skip


@pytest.mark.parametrize("case, args, status, says", CASES, ids=[c[0] for c in CASES])
def test_a_hostile_farm_option_is_refused_at_once(tmp_path, case, args, status, says):
    scene = tmp_path / "missing.blend" if status == 1 else SAMPLE
    start = time.monotonic()
    run = farm(scene, "-o", tmp_path / "out_####.png", *args)
    assert time.monotonic() - start < 30, case
    assert run.returncode == status, run.stderr
    assert says in run.stderr, run.stderr
    assert "Traceback" not in run.stderr
    assert list(tmp_path.iterdir()) == []


def test_frame_lists_parse_in_linear_time_and_are_never_listed_frame_by_frame():
    start = time.perf_counter()
    frames = parse_frames(",".join(f"{2 * i}" for i in range(50_000)) + ",0-1000000" * 50_000)
    assert time.perf_counter() - start < 5  # 10^5 runs; the quadratic parse took minutes
    assert len(frames) == 1_000_001  # the odd frames follow the even ones, as listed
    assert list(parse_frames("5,1-3,2-7,-2")) == [5, 1, 2, 3, 4, 6, 7, -2]
    every = parse_frames(f"{-LAST_FRAME}-{LAST_FRAME}")
    plan = Plan("s.blend", every, None, (1, 1), chunk=1)  # tasks made as submitted
    assert len(plan) == 2 * LAST_FRAME + 1 and len(every.runs) == 1
    first = next(iter(plan))
    assert first.frames == (-LAST_FRAME,)
    with pytest.raises(FarmError, match="at most 65,536"):
        Plan("s.blend", every, None, (257, 256), chunk=1)


def test_a_script_with_a_syntax_error_is_named_before_any_cluster_starts(tmp_path):
    (tmp_path / "scene.lua").write_text(BAD_SYNTAX)
    (tmp_path / "tmp").mkdir()
    start = time.monotonic()
    run = farm(tmp_path / "scene.lua", "-o", tmp_path / "out.png", tmp=tmp_path / "tmp")
    assert time.monotonic() - start < 30
    assert run.returncode == 1, run.stderr
    assert run.stderr.strip().startswith("error: scene.lua:2: "), run.stderr
    assert "Traceback" not in run.stderr
    assert list((tmp_path / "tmp").iterdir()) == []


def test_a_finished_blend_job_leaves_nothing_in_tmpdir(tmp_path):
    """Its Blenders (the probe's, the workers'), their blender_XXXXXX folders, the
    workers' dask-scratch-space: all in one folder of the job's, gone with it."""
    if subprocess.run(["which", "blender"], capture_output=True).returncode != 0:
        pytest.skip("no blender on PATH: run `make setup`")
    (tmp_path / "tmp").mkdir()
    run = farm(SAMPLE, "-o", tmp_path / "out_####.png", "--workers", "1", "--blender", BLENDER,
               tmp=tmp_path / "tmp", timeout=600)  # fmt: skip
    assert run.returncode == 0, run.stderr[-3000:]
    assert (tmp_path / "out_0001.png").is_file()
    assert list((tmp_path / "tmp").iterdir()) == []
