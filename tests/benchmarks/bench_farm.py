"""The farm's speed-up on this machine: the report's final scene (sample_blends/
final_scene.blend, as `blender -b` renders it) by one `blender -b` process with one render
thread, against `python -m core farm` on a LocalCluster of two single-threaded workers, the
frame split in two borders. Both are whole processes, Blender's start-up included, run in
turn ROUNDS times; the medians are compared.

farm_speedup_2_workers: single-process time over the farm's (2 is the ideal on two cores);
farm_overhead_s: the farm's time beyond its busiest worker's tasks (the cluster's start,
scheduling, sending the borders back, stitching). Also checks that the stitched frame is
the single render's pixels. Writes results/farm.png.
"""

import os
import re
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


def main():
    RESULTS.mkdir(exist_ok=True)
    env = environment()
    folder = Path(tempfile.mkdtemp(prefix="whitted-bench-farm-"))
    single = ["blender", "-b", "--python-use-system-env", str(SCENE), "--addons", "whitted",
              "-E", "WHITTED", "--python-expr", ONE_THREAD, "-o", f"{folder}/single_####",
              "-F", "PNG", "-f", "1"]  # fmt: skip
    farm = [sys.executable, "-m", "core", "farm", str(SCENE), "--split", "2x1", "--workers",
            "2", "--threads", "1", "--blender", "blender --python-use-system-env",
            "-o", f"{folder}/farm_####.png"]  # fmt: skip
    single_s, farm_s, overheads = [], [], []
    for _ in range(ROUNDS):
        seconds, _ = timed(single, env)
        single_s.append(seconds)
        seconds, out = timed(farm, env)
        farm_s.append(seconds)
        busiest = float(re.search(r"busiest worker ([\d.]+) s", out)[1])
        overheads.append(seconds - busiest)
    same = np.array_equal(np.asarray(Image.open(folder / "single_0001.png")),
                          np.asarray(Image.open(folder / "farm_0001.png")))  # fmt: skip
    assert same, "the farm's stitched frame differs from the single render"
    speedup = statistics.median(single_s) / statistics.median(farm_s)
    print(f"farm_single_process_s: {statistics.median(single_s):.2f}")
    print(f"farm_two_workers_s: {statistics.median(farm_s):.2f}")
    print(f"farm_speedup_2_workers: {speedup:.2f}")
    print(f"farm_overhead_s: {statistics.median(overheads):.2f}")
    figure, axes = plt.subplots(figsize=(6, 3.2))
    axes.barh(
        ["one blender -b,\none thread", "farm: 2 workers,\n2 borders"],
        [statistics.median(single_s), statistics.median(farm_s)],
        color="#4a7ab5",
    )
    axes.set_xlabel(f"seconds, whole processes (median of {ROUNDS})")
    axes.set_title(f"Final scene: farm speed-up {speedup:.2f}x on two cores")
    figure.tight_layout()
    figure.savefig(RESULTS / "farm.png", dpi=110)


if __name__ == "__main__":
    main()
