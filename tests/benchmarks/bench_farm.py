"""The farm's speed-up on this machine: the report's final scene (sample_blends/
final_scene.blend, as `blender -b` renders it) by one `blender -b` process with one render
thread, against `python -m core farm` on two single-threaded workers, the frame split in two
borders. Every figure is whole processes, Blender's start-up and the farm command's included,
run in turn, round after round; each round's ratio is taken, and the median of the rounds.

- farm_speedup_2_workers: a farm as it runs in production, a `dask scheduler` and `dask
  worker --nworkers 2 --nthreads 1` already up (started once here, and given one job
  beforehand, as a farm's first job of the day opens its Blenders): each worker's Blender is
  warm, the scene open, so a border costs its render. 2 is the ideal on two cores.
- farm_speedup_2_workers_fresh_blender: the same cluster, a `blender -b` started for every
  task (--fresh-blender, what the farm did before its Blenders were kept).
- farm_speedup_2_workers_cold: `--scheduler local`, the command starting its own cluster and
  Blenders (a one-off job on a desktop).
- farm_overhead_s: the production farm's time beyond its busiest worker's tasks (the farm
  command's start, scheduling, sending the borders back, stitching).
- farm_border_cost_ms: what one more border costs the production farm, from a 2 x 1 and an
  8 x 8 split of the same frame.
- farm_speedup_2_workers_large: the production farm at twice the resolution (split 2 x 2).
Checks that each stitched frame is the single render's pixels. Writes results/farm.png.
"""

import os
import re
import socket
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from PIL import Image  # noqa: E402

ROOT = Path(__file__).resolve().parents[2]
RESULTS = Path(__file__).resolve().parent / "results"
SCENE = ROOT / "sample_blends" / "final_scene.blend"
ROUNDS = 3
ONE_THREAD = "import bpy; r = bpy.context.scene.render; r.threads_mode = 'FIXED'; r.threads = 1"
BLENDER = "blender --python-use-system-env"


def environment():
    site = ROOT / ".venv" / "lib" / "python3.11" / "site-packages"
    env = dict(os.environ, PYTHONPATH=f"{ROOT}{os.pathsep}{site}")
    env.setdefault("BLENDER_USER_SCRIPTS", str(ROOT / ".build" / "blender_scripts"))
    return env


def timed(command, env):
    start = time.perf_counter()
    done = subprocess.run(command, env=env, cwd=ROOT, capture_output=True, text=True)
    if done.returncode != 0:
        sys.exit(f"{command[:4]} failed:\n{done.stdout[-2000:]}{done.stderr[-2000:]}")
    return time.perf_counter() - start, done.stdout


def single_command(scene: Path, folder: Path):
    return ["blender", "-b", "--python-use-system-env", str(scene), "--addons", "whitted",
            "-E", "WHITTED", "--python-expr", ONE_THREAD, "-o", f"{folder}/single_####",
            "-F", "PNG", "-f", "1"]  # fmt: skip


def farm_command(scene: Path, folder: Path, scheduler: str, split: str, *extra: str):
    return [sys.executable, "-m", "core", "farm", str(scene), "--frames", "1", "--split", split,
            "--scheduler", scheduler, "--workers", "2", "--threads", "1", "--blender", BLENDER,
            *extra, "-o", f"{folder}/farm_####.png"]  # fmt: skip


def busiest(out: str) -> float:
    return float(re.search(r"busiest worker ([\d.]+) s", out)[1])


def same_pixels(folder: Path, scene: Path) -> None:
    same = np.array_equal(np.asarray(Image.open(folder / "single_0001.png")),
                          np.asarray(Image.open(folder / "farm_0001.png")))  # fmt: skip
    assert same, f"the farm's stitched frame of {scene.name} differs from the single render"


class StandingCluster:
    """`dask scheduler` and `dask worker` as a farm's hosts run them, here on this machine."""

    def __init__(self, env):
        with socket.socket() as probe:
            probe.bind(("127.0.0.1", 0))
            port = probe.getsockname()[1]
        self.address = f"tcp://127.0.0.1:{port}"
        dask = [sys.executable, "-m", "dask"]
        quiet = dict(env=env, cwd=ROOT, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        self.processes = [subprocess.Popen([*dask, "scheduler", "--host", "127.0.0.1", "--port",
                                            str(port), "--no-dashboard"], **quiet)]  # fmt: skip
        time.sleep(2)
        workers = [*dask, "worker", self.address, "--nworkers", "2", "--nthreads", "1",
                   "--no-dashboard"]  # fmt: skip
        self.processes.append(subprocess.Popen(workers, **quiet))

    def close(self):
        for process in reversed(self.processes):
            process.terminate()
            process.wait(timeout=60)


def measure(env, folder: Path, farm: StandingCluster, large: Path) -> dict:
    """Per-round ratios and times, the variants interleaved within each round."""
    rows = {key: [] for key in ("single", "warm", "fresh", "cold", "overhead", "fine",
                                "large_single", "large_warm")}  # fmt: skip
    for scene in (SCENE, large):  # a first job of the day: the workers open their Blenders
        timed(farm_command(scene, folder, farm.address, "2x1"), env)
    for round_ in range(ROUNDS):
        single_s, _ = timed(single_command(SCENE, folder), env)
        warm_s, out = timed(farm_command(SCENE, folder, farm.address, "2x1"), env)
        same_pixels(folder, SCENE)
        fresh_s, _ = timed(farm_command(SCENE, folder, farm.address, "2x1", "--fresh-blender"),
                           env)  # fmt: skip
        cold_s, _ = timed(farm_command(SCENE, folder, "local", "2x1"), env)
        fine_s, _ = timed(farm_command(SCENE, folder, farm.address, "8x8"), env)
        same_pixels(folder, SCENE)
        for key, value in (("single", single_s), ("warm", warm_s), ("fresh", fresh_s),
                           ("cold", cold_s), ("overhead", warm_s - busiest(out)),
                           ("fine", fine_s)):  # fmt: skip
            rows[key].append(value)
        if round_ < 2:
            rows["large_single"].append(timed(single_command(large, folder), env)[0])
            rows["large_warm"].append(timed(farm_command(large, folder, farm.address, "2x2"),
                                            env)[0])  # fmt: skip
            same_pixels(folder, large)
    return rows


def ratio(rows, over: str, under: str) -> float:
    return statistics.median(a / b for a, b in zip(rows[over], rows[under], strict=False))


def main():
    RESULTS.mkdir(exist_ok=True)
    env = environment()
    folder = Path(tempfile.mkdtemp(prefix="whitted-bench-farm-"))
    large = folder / "final_scene_200.blend"
    enlarge = ("import bpy; bpy.context.scene.render.resolution_percentage = 200; "
               f"bpy.ops.wm.save_as_mainfile(filepath={str(large)!r})")  # fmt: skip
    timed(["blender", "-b", str(SCENE), "--python-expr", enlarge], env)
    farm = StandingCluster(env)
    try:
        rows = measure(env, folder, farm, large)
    finally:
        farm.close()
    median = {key: statistics.median(values) for key, values in rows.items()}
    speedup = ratio(rows, "single", "warm")
    figures = {
        "farm_single_process_s": median["single"],
        "farm_two_workers_s": median["warm"],
        "farm_speedup_2_workers": speedup,
        "farm_speedup_2_workers_fresh_blender": ratio(rows, "single", "fresh"),
        "farm_speedup_2_workers_cold": ratio(rows, "single", "cold"),
        "farm_overhead_s": median["overhead"],
        # 64 borders against 2, 31 of them per worker beyond the first
        "farm_border_cost_ms": (median["fine"] - median["warm"]) / 31 * 1000,
        "farm_speedup_2_workers_large": ratio(rows, "large_single", "large_warm"),
    }
    for name, value in figures.items():
        print(f"{name}: {value:.2f}")
    figure, axes = plt.subplots(figsize=(7, 3.8))
    labels = ["one blender -b", "farm, warm Blenders", "farm, a Blender per task",
              "farm, own local cluster", "farm, warm, 8 x 8 borders"]  # fmt: skip
    values = [median[k] for k in ("single", "warm", "fresh", "cold", "fine")]
    axes.barh(labels, values, color=["#999999", "#4a7ab5", "#8fb0d8", "#8fb0d8", "#8fb0d8"])
    axes.invert_yaxis()
    axes.set_xlabel("seconds, whole processes, one render thread per process")
    axes.set_title(f"Final scene 500 x 500 on two workers: {speedup:.2f}x")
    figure.tight_layout()
    figure.savefig(RESULTS / "farm.png", dpi=110)


if __name__ == "__main__":
    main()
