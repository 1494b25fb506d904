"""Smoke benchmark: kernel compile time (cold and cached) and render speed of a sphere scene.

Cold compile runs in a subprocess with an empty kernel cache; the cached load in another
subprocess reusing it; render time in this process, as a ratio across resolutions so that a
noisy shared machine still gives comparable numbers. Writes results/smoke.png and smoke.csv.
"""

import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

from core import Camera, Material, PointLight, RenderSettings, Scene, Sphere, render

RESULTS = Path(__file__).resolve().parent / "results"
ROOT = Path(__file__).resolve().parents[2]


def spheres_scene(count=16):
    rng = np.random.default_rng(1)
    shapes = [Sphere("Ground", Material((0.5, 0.5, 0.5)), np.diag([1e3, 1e3, 1e3, 1.0]))]
    shapes[0].world_from_object[2, 3] = -1e3
    for i in range(count):
        m = np.diag([0.6, 0.6, 0.6, 1.0])
        m[:3, 3] = (*rng.uniform(-4, 4, 2), 0.6)
        shapes.append(Sphere(f"S{i}", Material(tuple(rng.uniform(0.1, 0.9, 3)), (0.5,) * 3, 30), m))
    light = PointLight((4, -6, 10), (150, 150, 150), (0, 0, 1))
    camera = Camera((0, -12, 6), (0, 12, -6), (0, 0, 1), 45)
    return Scene(camera, shapes, [light], ambient=(0.05,) * 3, background=(0.1, 0.1, 0.15))


def kernel_load_seconds(cache_dir):
    code = (
        "import time; t = time.perf_counter(); from core.driver import render; "
        "from tests.benchmarks.bench_smoke import spheres_scene; from core import RenderSettings; "
        "first = []; tile = lambda *a: first or first.append(time.perf_counter() - t); "
        "out = render(spheres_scene(), RenderSettings(64, 64, pixel_samples=1), on_tile=tile); "
        "print(out.stats.kernel_s, out.stats.kernel_source, first[0])"
    )
    env = dict(os.environ, WHITTED_CACHE_DIR=str(cache_dir))
    run = subprocess.run(
        [sys.executable, "-c", code], env=env, cwd=ROOT, capture_output=True, text=True, check=True
    )
    seconds, source, first_tile = run.stdout.split()
    return float(seconds), source, float(first_tile)


def main():
    with tempfile.TemporaryDirectory() as cache:
        cold, cold_source, _ = kernel_load_seconds(cache)
        warm, warm_source, first_tile = kernel_load_seconds(cache)
    assert (cold_source, warm_source) == ("compiled", "cache"), (cold_source, warm_source)
    print(f"compile_cold_s: {cold:.3f}")
    print(f"kernel_load_cached_s: {warm:.3f}")
    print(f"start_to_first_tile_cached_s: {first_tile:.3f}")

    scene = spheres_scene()
    render(scene, RenderSettings(8, 8, pixel_samples=1))  # kernels into memory
    rows = []
    for size in (64, 128, 256, 512):
        start = time.perf_counter()
        out = render(scene, RenderSettings(size, size, pixel_samples=1))
        seconds = time.perf_counter() - start
        rows.append((size, seconds, size * size / seconds / 1e6, out.stats.threads))
        print(f"render_{size}_s: {seconds:.4f}")
    size, seconds, mrays, threads = rows[-1]
    print(f"camera_mrays_per_s_512: {mrays:.3f}")
    print(f"threads: {threads}")
    print(f"time_ratio_512_over_256: {rows[-1][1] / rows[-2][1]:.2f}")
    write_results(rows)


def write_results(rows):
    RESULTS.mkdir(exist_ok=True)
    with open(RESULTS / "smoke.csv", "w") as f:
        f.write("size,seconds,camera_mrays_per_s,threads\n")
        f.writelines(f"{s},{t:.6f},{m:.6f},{n}\n" for s, t, m, n in rows)
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(5, 3.5))
    pixels = [s * s for s, *_ in rows]
    ax.loglog(pixels, [t for _, t, *_ in rows], "o-", label="render time")
    ax.set_xlabel("pixels")
    ax.set_ylabel("seconds (wall)")
    ax.set_title("Smoke: 17 spheres, 1 point light")
    ax.legend()
    fig.tight_layout()
    fig.savefig(RESULTS / "smoke.png", dpi=100)
    print(f"chart: {RESULTS / 'smoke.png'}")


if __name__ == "__main__":
    main()
