"""The report's final scene, Whitted against POV-Ray 3.7 in the same run, on the same geometry.

The scene is what the add-on exports from `sample_blends/final_scene.blend`; `povray_scene`
writes it for POV-Ray with the same shapes, CSG trees, teapot triangles and normals,
textures, light, camera and settings (3 x 3 camera rays, 40 area-light shadow rays, depth 50).

First a check that the two scenes are the same: both renderers draw each object in a flat
colour of its own (one ray through each pixel centre), and the object masks must agree on
all but the pixels along silhouettes.

Then, interleaved, three rounds of: Whitted through `blender -b ... -E WHITTED -f 1` (the
command a farm runs), POV-Ray as it shades by default (an area light's colour averaged over
its shadow rays, shaded once from its centre), and POV-Ray with `area_illumination on`
(shaded at every light sample, as Whitted does). Prints, as `name: value` lines:
  final_scene_povray_mask_agreement       share of pixels where both see the same object
  final_scene_whitted_render_s            Whitted's render time (median), and its process
  final_scene_whitted_process_s
  final_scene_povray_trace_s              POV-Ray's trace time (median), and its process
  final_scene_povray_process_s
  final_scene_povray_ratio                Whitted's render time over POV-Ray's trace time
  final_scene_povray_process_ratio        the same for the whole processes
  final_scene_povray_area_illumination_ratio   against POV-Ray shading every light sample
and writes results/speed_scaling.png (.csv): render time against shadow rays per shading
point and against image size, both renderers on the same axes (Whitted in-process).
"""

import csv
import dataclasses
import os
import re
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import matplotlib
import numpy as np
from PIL import Image

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

import core  # noqa: E402
from tests.benchmarks.bench_final_scene import render as blender_render  # noqa: E402
from tests.benchmarks.final_scene_data import final_scene  # noqa: E402
from tests.benchmarks.povray_scene import povray_command, write_pov  # noqa: E402

RESULTS = Path(__file__).resolve().parent / "results"
ROUNDS = 3
# Pixels along silhouettes may see either object: a ray through a pixel centre passes an
# edge on one side or the other by a rounding. More than this would be a different scene.
MIN_MASK_AGREEMENT = 0.995
TRACE_TIME = re.compile(r"Trace Time:.*\((?P<seconds>[\d.]+) seconds\)")
SHADOW_SAMPLES = (1, 4, 16, 40, 64)
SIZES = (100, 200, 300, 400, 500)


def threads() -> int:
    return len(os.sched_getaffinity(0))


def povray(pov: Path, settings, out: Path, **options) -> tuple[float, float]:
    """Render with POV-Ray: (wall seconds of the process, its trace time); options go to
    povray_command (anti-aliasing, file format)."""
    command = povray_command(pov, out, settings, threads(), **options)
    start = time.perf_counter()
    done = subprocess.run(command, cwd=pov.parent, capture_output=True, text=True)
    seconds = time.perf_counter() - start
    match = TRACE_TIME.search(done.stderr)
    if done.returncode != 0 or match is None:
        sys.exit(f"povray failed ({' '.join(command)}):\n{done.stderr[-3000:]}")
    return seconds, float(match["seconds"])


def with_material(shape, material: core.Material):
    """A copy of the shape (and of a CSG tree's operands) in one material."""
    copy = dataclasses.replace(shape, material=material)
    if isinstance(shape, core.Csg):
        copy.left = with_material(shape.left, material)
        copy.right = with_material(shape.right, material)
    return copy


def object_id_scene(scene: core.Scene) -> core.Scene:
    """Shape k in flat red (k + 1) / 255 under ambient light 1, no lights, black background."""
    shapes = []
    for k, shape in enumerate(scene.shapes):
        flat = core.Material(name=f"object {k}", diffuse=((k + 1) / 255.0, 0.0, 0.0),
                             specular=(0.0, 0.0, 0.0))  # fmt: skip
        shapes.append(with_material(shape, flat))
    return core.Scene(camera=scene.camera, shapes=shapes, lights=[], ambient=(1.0, 1.0, 1.0),
                      background=(0.0, 0.0, 0.0))  # fmt: skip


def mask_agreement(scene: core.Scene, settings, folder: Path) -> float:
    ids = object_id_scene(scene)
    flat = dataclasses.replace(settings, pixel_samples=1, max_depth=0, threads=threads())
    whitted = core.render(ids, flat).image[:, :, 0]
    whitted_ids = np.round(whitted * 255.0).astype(int)
    pov = write_pov(ids, flat, folder / "object_ids")
    out = pov.parent / "ids.png"
    povray(pov, flat, out)
    pov_ids = np.asarray(Image.open(out).convert("RGB"))[:, :, 0].astype(int)
    for k, shape in enumerate(scene.shapes):
        print(f"  {shape.name}: {np.sum(whitted_ids == k + 1)} pixels in Whitted, "
              f"{np.sum(pov_ids == k + 1)} in POV-Ray")  # fmt: skip
    return float(np.mean(whitted_ids == pov_ids))


def timed_rounds(pov_default: Path, pov_each_sample: Path, settings, folder: Path) -> dict:
    times = {key: [] for key in ("whitted", "whitted_render", "pov", "pov_trace",
                                 "pov_each", "pov_each_trace")}  # fmt: skip
    for round_ in range(ROUNDS):
        seconds, summary = blender_render(settings.width)
        times["whitted"].append(seconds)
        times["whitted_render"].append(float(summary["render"]))
        seconds, trace = povray(pov_default, settings, folder / "final.png")
        times["pov"].append(seconds)
        times["pov_trace"].append(trace)
        seconds, trace = povray(pov_each_sample, settings, folder / "final_each_sample.png")
        times["pov_each"].append(seconds)
        times["pov_each_trace"].append(trace)
        print(f"  round {round_ + 1}: Whitted {times['whitted_render'][-1]:.2f} s, POV-Ray "
              f"{times['pov_trace'][-1]:.2f} s, with area_illumination "
              f"{times['pov_each_trace'][-1]:.2f} s", flush=True)  # fmt: skip
    return {key: statistics.median(values) for key, values in times.items()}


def scaling(scene: core.Scene, settings, folder: Path) -> list[tuple]:
    """(axis, value, Whitted render s, POV-Ray trace s) over shadow rays and image sizes."""
    rows = []
    # The first render of a process pays for loading what it needs once: not a point's cost
    core.render(scene, dataclasses.replace(settings, width=16, height=16))
    variants = [("shadow rays per shading point", n, dataclasses.replace(settings,
                width=300, height=300, shadow_samples=n)) for n in SHADOW_SAMPLES]  # fmt: skip
    variants += [
        (
            "image size (pixels per side)",
            size,
            dataclasses.replace(settings, width=size, height=size),
        )
        for size in SIZES
    ]
    for axis, value, varied in variants:
        varied = dataclasses.replace(varied, threads=threads())
        whitted = core.render(scene, varied).stats.render_s
        pov = write_pov(scene, varied, folder / "scaling")
        _, trace = povray(pov, varied, pov.parent / "out.png")
        rows.append((axis, value, whitted, trace))
        print(f"  {axis} {value}: Whitted {whitted:.2f} s, POV-Ray {trace:.2f} s", flush=True)
    return rows


def chart(rows: list[tuple]) -> None:
    with open(RESULTS / "speed_scaling.csv", "w", newline="") as f:
        writer = csv.writer(f)
        writer.writerow(["axis", "value", "whitted_render_s", "povray_trace_s"])
        writer.writerows(rows)
    axes_names = list(dict.fromkeys(r[0] for r in rows))
    fig, axes = plt.subplots(1, len(axes_names), figsize=(11, 4))
    for ax, name in zip(axes, axes_names, strict=True):
        picked = [r for r in rows if r[0] == name]
        x = [r[1] for r in picked]
        ax.plot(x, [r[2] for r in picked], "o-", label="Whitted", color="#4a7ab5")
        ax.plot(x, [r[3] for r in picked], "s--", label="POV-Ray 3.7", color="#c0504d")
        ax.set_xlabel(name)
        ax.set_ylabel("render time (s)")
        ax.set_ylim(bottom=0)
        ax.grid(alpha=0.3)
        ax.legend()
    axes[0].set_title("300 x 300, 3 x 3 camera rays")
    axes[1].set_title("40 shadow rays, 3 x 3 camera rays")
    fig.suptitle(f"The report's final scene, {threads()} threads: how each cost grows")
    fig.tight_layout()
    fig.savefig(RESULTS / "speed_scaling.png", dpi=120)


def main():
    if shutil.which("povray") is None:
        sys.exit("POV-Ray is missing: `make bench` installs Debian's povray package")
    RESULTS.mkdir(exist_ok=True)
    scene, settings = final_scene()
    with tempfile.TemporaryDirectory() as name:
        folder = Path(name)
        agreement = mask_agreement(scene, settings, folder)
        print(f"final_scene_povray_mask_agreement: {agreement:.4f}")
        if agreement < MIN_MASK_AGREEMENT:
            sys.exit("the POV-Ray scene does not draw the same objects: no timing")
        pov_default = write_pov(scene, settings, folder / "default")
        pov_each = write_pov(scene, settings, folder / "each_sample", area_illumination=True)
        median = timed_rounds(pov_default, pov_each, settings, folder)
        print(f"final_scene_whitted_render_s: {median['whitted_render']:.2f}")
        print(f"final_scene_whitted_process_s: {median['whitted']:.2f}")
        print(f"final_scene_povray_trace_s: {median['pov_trace']:.2f}")
        print(f"final_scene_povray_process_s: {median['pov']:.2f}")
        print(f"final_scene_povray_area_illumination_trace_s: {median['pov_each_trace']:.2f}")
        ratio = median["whitted_render"] / median["pov_trace"]
        print(f"final_scene_povray_ratio: {ratio:.2f}")
        print(f"final_scene_povray_process_ratio: {median['whitted'] / median['pov']:.2f}")
        each = median["whitted_render"] / median["pov_each_trace"]
        print(f"final_scene_povray_area_illumination_ratio: {each:.2f}")
        chart(scaling(scene, settings, folder))


if __name__ == "__main__":
    main()
