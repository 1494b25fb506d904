"""Chart 5 of speed against accuracy: the report's final scene over a grid of settings.

The scene comes from sample_blends/final_scene.blend through the add-on's own export (the
bpy 5.0 module), then renders in the core at 128 x 128 for n x n grid camera rays (n = 1..8)
and 1 to 40 shadow rays in the scene's own pattern (stratified). Error is the RMSE against
a converged render of the same scene: 16 x 16 jittered camera rays and 64 Halton shadow rays
per shading point (patterns apart from the ones charted, so their own errors do not
cancel). Time is render time in this process, kernels loaded, best of 2.

The chart draws one line per anti-aliasing setting and the frontier (the settings no other
beats in both time and error), and marks Whitted's default (what RenderSettings and a new
Blender scene start with) and the report's setting (3 x 3 grid, 40 shadow rays). Prints, for
each of the two, _rmse, _s and _error_over_best (its error over the frontier's at the same
time: 1.0 on the frontier); whole_scene_shadow_knee (per anti-aliasing setting, the fewest
shadow rays within 3% of the error of the most); whole_scene_front. Writes
results/whole_scene.png and .csv.
"""

import csv
import dataclasses
import importlib
import math
import os
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from core import RenderSettings, render  # noqa: E402
from tests.benchmarks.bench_sampling import timed_render  # noqa: E402

ROOT = Path(__file__).resolve().parents[2]
RESULTS = Path(__file__).resolve().parent / "results"
SCENE = ROOT / "sample_blends" / "final_scene.blend"
SIZE = 128
SIDES = (1, 2, 3, 4, 6, 8)
SHADOW_COUNTS = (1, 2, 4, 9, 16, 40)
REPORT = (3, 40)


def final_scene():
    """(core.Scene, RenderSettings) of the final scene, exported as the engine does."""
    os.environ.setdefault("BLENDER_USER_SCRIPTS", str(ROOT / ".build" / "blender_scripts"))
    import bpy  # noqa: I001 (bpy first: it makes addon_utils importable)
    import addon_utils

    addon = addon_utils.enable("whitted", default_set=True, handle_error=None)
    if addon is None:
        raise SystemExit("the whitted add-on did not load (see the traceback above)")
    bpy.ops.wm.open_mainfile(filepath=str(SCENE))
    export = importlib.import_module("whitted.export")
    scene, settings, warnings = export.convert(bpy.context.evaluated_depsgraph_get())
    if warnings:
        raise SystemExit(f"the final scene exported with warnings: {warnings}")
    return scene, settings


def front(rows):
    """The settings no other setting beats in both time and error, fastest first."""
    best = []
    for r in sorted(rows, key=lambda r: (r[2], r[3])):
        if not best or r[3] < best[-1][3]:
            best.append(r)
    return best


def front_error_at(frontier, seconds):
    """The frontier's error at `seconds`, joining its points by straight lines in log-log."""
    times = np.log([r[2] for r in frontier])
    errors = np.log([r[3] for r in frontier])
    return float(np.exp(np.interp(math.log(seconds), times, errors)))


def shadow_knee(rows, side, within=0.03):
    """Fewest shadow rays whose error, at n x n camera rays, is within 3% of the most's."""
    mine = [r for r in rows if r[0] == side]
    floor = min(r[3] for r in mine)
    return min(r[1] for r in mine if r[3] <= floor * (1.0 + within))


def main():
    scene, blend_settings = final_scene()
    base = dataclasses.replace(blend_settings, width=SIZE, height=SIZE, region=None)
    default = RenderSettings()
    default_setting = (default.pixel_samples, default.shadow_samples)
    render(scene, dataclasses.replace(base, width=4, height=4))  # load the kernels
    converged = render(scene, dataclasses.replace(
        base, pixel_samples=16, pixel_sampling="jittered", shadow_samples=64,
        shadow_sampling="halton", seed=7)).image[..., :3].astype(float)  # fmt: skip
    rows = []
    for side in SIDES:
        for count in SHADOW_COUNTS:
            settings = dataclasses.replace(
                base, pixel_samples=side, pixel_sampling="grid", shadow_samples=count
            )
            image, seconds = timed_render(scene, settings)
            rmse = float(np.sqrt(np.mean((image - converged) ** 2)))
            rows.append((side, count, seconds, rmse))
            print(f"  whole scene {side}x{side} grid, {count:>2} shadow rays  {seconds:.3f} s  "
                  f"rmse {rmse:.5f}", flush=True)  # fmt: skip
    RESULTS.mkdir(exist_ok=True)
    with open(RESULTS / "whole_scene.csv", "w", newline="") as f:
        writer = csv.writer(f)
        writer.writerow(["pixel_samples_per_side", "shadow_rays", "render_s", "rmse"])
        writer.writerows(rows)
    frontier = front(rows)
    fig, ax = plt.subplots(figsize=(7, 5))
    for side in SIDES:
        mine = [r for r in rows if r[0] == side]
        ax.plot([r[2] for r in mine], [r[3] for r in mine], "o-", label=f"{side} x {side} grid")
        for r in mine:
            ax.annotate(str(r[1]), (r[2], r[3]), fontsize=7, xytext=(3, 3),
                        textcoords="offset points")  # fmt: skip
    ax.plot([r[2] for r in frontier], [r[3] for r in frontier], "k:", label="best at each time")
    for label, (side, count), style in (("default", default_setting, "k*"),
                                        ("report", REPORT, "rs")):  # fmt: skip
        r = next(r for r in rows if (r[0], r[1]) == (side, count))
        fill = "full" if label == "default" else "none"
        ax.plot(r[2], r[3], style, markersize=13, fillstyle=fill,
                label=f"{label}: {side} x {side}, {count} shadow rays")  # fmt: skip
        name = f"whole_scene_{label}"
        print(f"{name}_rmse: {r[3]:.5f}")
        print(f"{name}_s: {r[2]:.3f}")
        # 1.0 on the frontier; 2.0 means the best setting of the same time has half the error
        print(f"{name}_error_over_best: {r[3] / front_error_at(frontier, r[2]):.2f}")
    knees = {side: shadow_knee(rows, side) for side in SIDES}
    print("whole_scene_shadow_knee: " + ", ".join(f"{k}x{k}: {v}" for k, v in knees.items()))
    print("whole_scene_front: " + ", ".join(f"{r[0]}x{r[0]}/{r[1]}" for r in frontier))
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel(f"render time (s), {SIZE} x {SIZE}")
    ax.set_ylabel("RMSE against a converged render")
    ax.set_title("Final scene: error against time (labels: shadow rays)")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(RESULTS / "whole_scene.png", dpi=120)
    plt.close(fig)


if __name__ == "__main__":
    main()
