"""The report's final scene through the real `blender -b` command line (Blender 3.4).

Prints, as `name: value` lines:
  final_scene_500_s, final_scene_256_s   wall time of the whole `blender -b` process (warm
                                          kernel cache): start-up, export, render, PNG
  final_scene_mrays_per_s                 rays cast (camera, bounce and shadow) per second of
                                          render time, 500 x 500
  final_scene_export_s, final_scene_render_s, final_scene_rays_cast, final_scene_shadow_rays
  final_scene_kernel_cold_s, final_scene_kernel_cached_s   compile (empty cache: the warm-up
                                          process and the load after it) and load
  blender_startup_s                       the same process without the render (add-on import)
and where the render time goes: the 256 x 256 frame again with one feature taken out at a
time (its share is 1 - that time / the full time). Writes results/final_scene.png and .csv.
"""

import csv
import os
import re
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

ROOT = Path(__file__).resolve().parents[2]
RESULTS = Path(__file__).resolve().parent / "results"
SCENE = ROOT / "sample_blends" / "final_scene.blend"
SUMMARY = re.compile(
    r"Whitted \| \d+x\d+ \| export (?P<export>[\d.]+) s \| kernels (?P<source>\w+) "
    r"(?P<kernel>[\d.]+) s \| render (?P<render>[\d.]+) s \| (?P<rays>[\d.]+) M rays "
    r"\((?P<shadow>[\d.]+) M shadow\)"
)
WARMUP = re.compile(r"Whitted: kernels ready in (?P<seconds>[\d.]+) s")
# Each takes one thing out of the scene (Python run after the file loads)
ABLATIONS = {
    "no area-light shadows (1 sample)": "s.whitted.shadow_samples = 1",
    "no supersampling (1 ray/pixel)": "s.whitted.pixel_samples = 1",
    "no reflections": "[setattr(m.whitted, 'reflectivity', 0.0) for m in bpy.data.materials]",
    "no teapot": "bpy.data.objects['Teapot'].hide_render = True",
    "no CSG (operands hidden)": (
        "[m.__setattr__('show_render', False) for o in bpy.data.objects for m in o.modifiers]"
    ),
}


def blender(*args, cache=None, python=""):
    """Run `blender -b` on the final scene; (wall seconds, parsed summary or None)."""
    env = dict(os.environ)
    env["BLENDER_USER_SCRIPTS"] = str(ROOT / ".build" / "blender_scripts")
    site = ROOT / ".venv" / "lib" / "python3.11" / "site-packages"
    env["PYTHONPATH"] = f"{ROOT}:{site}"
    env["WHITTED_CACHE_DIR"] = cache or env.get(
        "WHITTED_CACHE_DIR", str(ROOT / ".cache" / "kernels")
    )
    command = ["blender", "-b", "--python-use-system-env", "--addons", "whitted", str(SCENE)]
    if python:
        command += ["--python-expr", f"import bpy; s = bpy.context.scene; {python}"]
    start = time.perf_counter()
    done = subprocess.run(command + list(args), env=env, capture_output=True, text=True)
    seconds = time.perf_counter() - start
    if done.returncode != 0 or "Traceback" in done.stdout + done.stderr:
        sys.exit(f"blender failed:\n{done.stdout[-3000:]}\n{done.stderr[-3000:]}")
    match = SUMMARY.search(done.stdout)
    if not match:
        return seconds, None
    # With an empty cache the compile happens in the warm-up process, before the render
    warmup = WARMUP.search(done.stdout)
    return seconds, {**match.groupdict(), "warmup": float(warmup["seconds"]) if warmup else 0.0}


def render(size, python="", cache=None):
    out = Path(tempfile.mkdtemp()) / "frame_####"
    resize = f"s.render.resolution_x = s.render.resolution_y = {size}; "
    seconds, summary = blender("-E", "WHITTED", "-o", str(out), "-F", "PNG", "-f", "1",
                               cache=cache, python=resize + python)  # fmt: skip
    if summary is None:
        sys.exit("the render printed no Whitted summary line")
    return seconds, summary


def best_of(runs, run):
    return min((run() for _ in range(runs)), key=lambda result: result[0])


def main():
    RESULTS.mkdir(exist_ok=True)
    with tempfile.TemporaryDirectory() as empty:
        _, cold = render(16, cache=empty)
    print(f"final_scene_kernel_cold_s: {cold['warmup'] + float(cold['kernel']):.1f}")
    startup = min(blender()[0] for _ in range(2))
    print(f"blender_startup_s: {startup:.2f}")
    full_256 = best_of(2, lambda: render(256))
    seconds_500, summary = best_of(2, lambda: render(500))
    render_s = float(summary["render"])
    print(f"final_scene_kernel_cached_s: {float(summary['kernel']):.3f} ({summary['source']})")
    print(f"final_scene_export_s: {float(summary['export']):.3f}")
    print(f"final_scene_render_s: {render_s:.2f}")
    print(f"final_scene_rays_cast: {float(summary['rays']) * 1e6:.3g}")
    print(f"final_scene_shadow_rays: {float(summary['shadow']) * 1e6:.3g}")
    print(f"final_scene_256_s: {full_256[0]:.2f}")
    print(f"final_scene_500_s: {seconds_500:.2f}")
    print(f"final_scene_mrays_per_s: {float(summary['rays']) / render_s:.2f}")

    full = float(full_256[1]["render"])
    rows = [("full scene", full, float(full_256[1]["rays"]))]
    for name, python in ABLATIONS.items():
        _, ablated = best_of(2, lambda python=python: render(256, python))
        seconds = float(ablated["render"])
        rows.append((name, seconds, float(ablated["rays"])))
        print(f"share of render time, {name}: {1.0 - seconds / full:.0%}")
    with open(RESULTS / "final_scene.csv", "w", newline="") as f:
        writer = csv.writer(f)
        writer.writerow(["variant (256 x 256)", "render_s", "mrays"])
        writer.writerows(rows)
    fig, ax = plt.subplots(figsize=(7, 3.5))
    ax.barh([r[0] for r in rows][::-1], [r[1] for r in rows][::-1], color="#4a7ab5")
    ax.set_xlabel("render time, 256 x 256, warm kernels (s)")
    ax.set_title("Final scene: render time with one feature taken out")
    fig.tight_layout()
    fig.savefig(RESULTS / "final_scene.png", dpi=120)


if __name__ == "__main__":
    main()
