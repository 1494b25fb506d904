"""What the render passes cost on the final scene (as `blender -b` renders it: 500 x 500,
3 x 3 camera rays, 40 shadow rays, depth 50), in-process on all cores.

Variants, each rendered ROUNDS times, interleaved, the fastest kept: no passes; the data
passes (depth, mist, normal, position, uv, indices); the light passes (diffuse colour,
shadow and Combined's six terms); Cryptomatte (objects and materials, 6 levels); all of them.
Prints passes_cost_ratio (all passes over none: the goal is at most 1.15) and a ratio per
group, checks that Combined is the same bits in every variant, and writes
results/passes_cost.png.
"""

import dataclasses
import os
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import core  # noqa: E402
from core.passes import PASS_NAMES  # noqa: E402
from tests.benchmarks.final_scene_data import final_scene  # noqa: E402

RESULTS = Path(__file__).resolve().parent / "results"
ROUNDS = 3
GROUPS = {
    "none": (),
    "data": ("depth", "mist", "normal", "position", "uv", "object_index", "material_index"),
    "light": (
        "diffuse_color",
        "shadow",
        "environment",
        "ambient",
        "diffuse",
        "specular",
        "reflection",
        "refraction",
    ),  # fmt: skip
    "cryptomatte": ("crypto_object", "crypto_material"),
    "all": PASS_NAMES,
}


def main():
    RESULTS.mkdir(exist_ok=True)
    scene, settings = final_scene()
    settings = dataclasses.replace(settings, threads=len(os.sched_getaffinity(0)))
    best, images = {}, {}
    for _ in range(ROUNDS):
        for group, passes in GROUPS.items():
            output = core.render(scene, dataclasses.replace(settings, passes=passes))
            best[group] = min(best.get(group, np.inf), output.stats.render_s)
            images[group] = output.image
    for group in GROUPS:
        assert np.array_equal(images[group], images["none"]), f"{group} changed Combined"
    print(f"passes_none_render_s: {best['none']:.2f}")
    ratios = {group: best[group] / best["none"] for group in GROUPS if group != "none"}
    for group, ratio in ratios.items():
        if group != "all":
            print(f"passes_{group}_cost_ratio: {ratio:.3f}")
    print(f"passes_cost_ratio: {ratios['all']:.3f}")
    figure, axes = plt.subplots(figsize=(6, 3.5))
    axes.bar(list(ratios), list(ratios.values()), color="#4a7ab5")
    axes.axhline(1.15, color="#b54a4a", linestyle="--", label="goal: at most 1.15")
    axes.axhline(1.0, color="black", linewidth=0.8)
    axes.set_ylim(0.9, max(1.25, max(ratios.values()) + 0.05))
    axes.set_ylabel("render time / no passes")
    axes.set_title(f"Final scene, passes on ({best['none']:.2f} s with none)")
    axes.legend()
    figure.tight_layout()
    figure.savefig(RESULTS / "passes_cost.png", dpi=110)


if __name__ == "__main__":
    main()
