"""The farm command's input, hostile cases, run as a user runs it (`python -m core farm`):
each refused at once with a message in the option's terms and a non-zero exit, never a wait
with no workers, a quadratic parse, a list of billions of frames in memory or a traceback;
and no job, finished, failed or cancelled, leaves a file in $TMPDIR (Blender's
blender_XXXXXX folders, Dask's dask-scratch-space)."""

import os
import random
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


def random_options(seed: int, count: int) -> list[tuple[str, str]]:
    """Random values for every numeric option of the farm command: numbers of every size
    and sign, and lists and pairs of them where the option takes those."""
    rng = random.Random(seed)

    def number() -> str:
        return rng.choice([
            str(rng.randint(-(10 ** rng.randint(0, 25)), 10 ** rng.randint(0, 25))),
            repr(rng.uniform(-1, 1) * 10.0 ** rng.randint(-30, 30)),
            rng.choice(["nan", "inf", "-0", "0", "1", "", " 7 ", "0x1f", "1_000"]),
        ])  # fmt: skip

    shapes = {
        "--workers": number, "--threads": number, "--chunk": number,
        "--split": lambda: f"{number()}x{number()}",
        "--frames": lambda: ",".join(
            f"{number()}-{number()}" if rng.random() < 0.5 else number()
            for _ in range(rng.randint(1, 5))
        ),
    }  # fmt: skip
    return [(option, shapes[option]()) for option in rng.choices(sorted(shapes), k=count)]


@pytest.mark.parametrize("option, value", random_options(40, 40))
def test_random_numeric_options_are_refused_or_taken_at_once(tmp_path, option, value):
    """A missing scene: every value taken ends at its message, every value refused at the
    option's; never a traceback, in seconds."""
    start = time.monotonic()
    run = farm(tmp_path / "missing.blend", "-o", tmp_path / "out_####.png", f"{option}={value}")
    assert time.monotonic() - start < 30
    assert "Traceback" not in run.stderr, run.stderr
    if run.returncode == 2:
        assert f"argument {option}: " in run.stderr, run.stderr
    else:
        assert run.returncode == 1 and "no such scene file" in run.stderr, run.stderr


def farm(*args, tmp=None, timeout=120):
    # The venv's packages for Debian's Blender (Python 3.11) that the workers start; not for
    # another Python running these tests (5.2's 3.13), which has its own
    same_python = sys.version_info[:2] == (3, 11)
    env = {**os.environ, "PYTHONPATH": f"{ROOT}{os.pathsep}{SITE}" if same_python else str(ROOT)}
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
    pytest.importorskip("distributed")  # the farm's own package, not every venv's
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
    pytest.importorskip("distributed")
    if subprocess.run(["which", "blender"], capture_output=True).returncode != 0:
        pytest.skip("no blender on PATH: run `make setup`")
    (tmp_path / "tmp").mkdir()
    run = farm(SAMPLE, "-o", tmp_path / "out_####.png", "--workers", "1", "--blender", BLENDER,
               tmp=tmp_path / "tmp", timeout=600)  # fmt: skip
    assert run.returncode == 0, run.stderr[-3000:]
    assert (tmp_path / "out_0001.png").is_file()
    assert list((tmp_path / "tmp").iterdir()) == []


@pytest.mark.parametrize(
    "output, says",
    [
        ("taken/out_####.png", "taken is a file, not a folder"),
        ("n" * 300 + "_####.png", "File name too long"),
        ("taken/deeper/out_####.png", "taken is a file, not a folder"),
    ],
)
def test_a_frame_path_that_cannot_be_written_is_named_before_any_cluster(tmp_path, output, says):
    (tmp_path / "taken").write_text("not a folder")
    start = time.monotonic()
    run = farm(SAMPLE, "-o", tmp_path / output)
    assert time.monotonic() - start < 30
    assert run.returncode == 1, run.stderr
    assert run.stderr.startswith(f"error: -o {tmp_path / output}: ") and says in run.stderr
    assert "Traceback" not in run.stderr


def test_a_frame_the_disk_refuses_is_a_farm_error_and_leaves_nothing(tmp_path):
    from core.farm.stitch import write_whole

    (tmp_path / "taken").write_text("not a folder")
    with pytest.raises(FarmError, match="taken is a file, not a folder"):
        write_whole(tmp_path / "taken" / "out_0001.png", b"png")
    (tmp_path / "dir").mkdir()
    (tmp_path / "dir" / "out_0001.png").mkdir()  # a folder where the frame goes
    with pytest.raises(FarmError, match="out_0001.png was not written"):
        write_whole(tmp_path / "dir" / "out_0001.png", b"png")
    assert sorted(p.name for p in (tmp_path / "dir").iterdir()) == ["out_0001.png"]
