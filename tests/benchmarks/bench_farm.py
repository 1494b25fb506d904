"""The farm's speed-up on this machine: the report's final scene (sample_blends/
final_scene.blend, as `blender -b` renders it) by one `blender -b` process with one render
thread, against `python -m core farm` on a LocalCluster of two single-threaded workers, the
frame split in two borders. Both are whole processes, Blender's start-up included, run in
turn ROUNDS times; the medians are compared.

farm_speedup_2_workers: single-process time over the farm's (2 is the ideal on two cores);
farm_overhead_s: the farm's time beyond its busiest worker's tasks (the cluster's start,
scheduling, sending the borders back, stitching). Every task pays a Blender start (1.3 s
here, the add-on's numba import 0.45 s of it) against a 6 s render, so the same comparison
is also made with the frame at twice the resolution (four times the work, split 2 x 2):
farm_speedup_2_workers_large. Also checks that each stitched frame is the single render's
pixels. Writes results/farm.png.
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


def compare(scene: Path, split: str, folder: Path, env: dict, rounds: int):
    """(single-process seconds, farm seconds, farm overheads), median of `rounds` each."""
    single = ["blender", "-b", "--python-use-system-env", str(scene), "--addons", "whitted",
              "-E", "WHITTED", "--python-expr", ONE_THREAD, "-o", f"{folder}/single_####",
              "-F", "PNG", "-f", "1"]  # fmt: skip
    farm = [sys.executable, "-m", "core", "farm", str(scene), "--frames", "1", "--split", split,
            "--workers", "2", "--threads", "1", "--blender", "blender --python-use-system-env",
            "-o", f"{folder}/farm_####.png"]  # fmt: skip
    single_s, farm_s, overheads = [], [], []
    for _ in range(rounds):
        seconds, _ = timed(single, env)
        single_s.append(seconds)
        seconds, out = timed(farm, env)
        farm_s.append(seconds)
        busiest = float(re.search(r"busiest worker ([\d.]+) s", out)[1])
        overheads.append(seconds - busiest)
    same = np.array_equal(np.asarray(Image.open(folder / "single_0001.png")),
                          np.asarray(Image.open(folder / "farm_0001.png")))  # fmt: skip
    assert same, f"the farm's stitched frame of {scene.name} differs from the single render"
    return tuple(statistics.median(v) for v in (single_s, farm_s, overheads))


def main():
    RESULTS.mkdir(exist_ok=True)
    env = environment()
    folder = Path(tempfile.mkdtemp(prefix="whitted-bench-farm-"))
    large = folder / "final_scene_200.blend"
    enlarge = ("import bpy; bpy.context.scene.render.resolution_percentage = 200; "
               f"bpy.ops.wm.save_as_mainfile(filepath={str(large)!r})")  # fmt: skip
    timed(["blender", "-b", str(SCENE), "--python-expr", enlarge], env)
    single_s, farm_s, overhead = compare(SCENE, "2x1", folder, env, ROUNDS)
    large_single, large_farm, _ = compare(large, "2x2", folder, env, 2)
    speedup, large_speedup = single_s / farm_s, large_single / large_farm
    print(f"farm_single_process_s: {single_s:.2f}")
    print(f"farm_two_workers_s: {farm_s:.2f}")
    print(f"farm_speedup_2_workers: {speedup:.2f}")
    print(f"farm_overhead_s: {overhead:.2f}")
    print(f"farm_speedup_2_workers_large: {large_speedup:.2f}")
    figure, axes = plt.subplots(figsize=(6.5, 3.4))
    labels = ["500 x 500:\none process", "farm, 2 borders", "1000 x 1000:\none process",
              "farm, 4 borders"]  # fmt: skip
    axes.barh(labels, [single_s, farm_s, large_single, large_farm],
              color=["#999999", "#4a7ab5", "#999999", "#4a7ab5"])  # fmt: skip
    axes.invert_yaxis()
    axes.set_xlabel("seconds, whole processes, one render thread per process")
    axes.set_title(f"Final scene on two workers: {speedup:.2f}x, {large_speedup:.2f}x at 2x size")
    figure.tight_layout()
    figure.savefig(RESULTS / "farm.png", dpi=110)


if __name__ == "__main__":
    main()
