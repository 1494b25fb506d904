"""Where the final scene's render time goes, measured by taking one thing away at a time.

The scene is what the add-on exports from `sample_blends/final_scene.blend`, rendered
in-process at its full settings (500 x 500, 3 x 3 camera rays, 40 shadow rays, depth 50) on
all cores, each variant twice, interleaved, the faster kept. Shares of the full render:
  camera rays      no lights and no bounces: camera rays, their hits, the pixel loop
  bounce rays      no lights, minus the above: reflected rays and their hits
  shading          every shape set to cast no shadow, minus no lights: the Phong sums over
                   the light's 40 points, the light's pyramid per shading point
  shadow tests of analytic shapes / CSG / meshes: the full render minus the render where
                   shapes of that kind cast no shadow
  shadow rays, the rest: what shadow rays cost beyond the three (their traversal and
                   bookkeeping); negative when taking one kind away shifts work to another
Also final_scene_culling_speedup: the render with every shadow ray tested against every
shape it may meet (RenderSettings.shadow_culling off) over the default, the same pixels, and
the share of shadow rays answered with no test. Writes results/final_breakdown.png (.csv).
"""

import csv
import dataclasses
import os
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import core  # noqa: E402
from tests.benchmarks.final_scene_data import final_scene  # noqa: E402

RESULTS = Path(__file__).resolve().parent / "results"
ROUNDS = 2
KINDS = {"analytic shapes": "analytic", "CSG": "csg", "meshes": "mesh"}


def kind_of(shape) -> str:
    if isinstance(shape, core.Csg):
        return "csg"
    return "mesh" if isinstance(shape, core.Mesh) else "analytic"


def variant(scene, settings, casting=("analytic", "csg", "mesh"), lit=True, **changes):
    shapes = [dataclasses.replace(s, casts_shadows=kind_of(s) in casting) for s in scene.shapes]
    lights = scene.lights if lit else []
    varied = dataclasses.replace(scene, shapes=shapes, lights=lights)
    return varied, dataclasses.replace(settings, **changes)


def main():
    RESULTS.mkdir(exist_ok=True)
    scene, settings = final_scene()
    settings = dataclasses.replace(settings, threads=len(os.sched_getaffinity(0)))
    every = tuple(KINDS.values())
    variants = {
        "full": variant(scene, settings),
        "culling off": variant(scene, settings, shadow_culling=False),
        "no lights, no bounces": variant(scene, settings, lit=False, max_depth=0),
        "no lights": variant(scene, settings, lit=False),
        "no shadows": variant(scene, settings, casting=()),
        **{f"no shadows of {name}": variant(scene, settings, tuple(k for k in every if k != kind))
           for name, kind in KINDS.items()},
    }  # fmt: skip
    best, outputs = {}, {}
    for _ in range(ROUNDS):
        for name, (varied, varied_settings) in variants.items():
            output = core.render(varied, varied_settings)
            best[name] = min(best.get(name, np.inf), output.stats.render_s)
            outputs[name] = output
    full = best["full"]
    shares = {
        "camera rays": best["no lights, no bounces"],
        "bounce rays": best["no lights"] - best["no lights, no bounces"],
        "shading": best["no shadows"] - best["no lights"],
    }
    for name in KINDS:
        shares[f"shadow tests of {name}"] = full - best[f"no shadows of {name}"]
    shares["shadow rays, the rest"] = full - sum(shares.values())
    print(f"final_scene_breakdown_render_s: {full:.2f}")
    for name, seconds in shares.items():
        key = name.replace(" ", "_").replace(",", "").lower()
        print(f"final_scene_share_{key}: {seconds / full:.2f}")
    stats = outputs["full"].stats
    same = np.array_equal(outputs["full"].image, outputs["culling off"].image)
    print(f"final_scene_culling_speedup: {best['culling off'] / full:.2f}")
    print(f"final_scene_culling_same_pixels: {same}")
    print(f"final_scene_shadow_rays_untested_share: "
          f"{stats.shadow_rays_unobstructed / stats.shadow_rays:.2f}")  # fmt: skip
    with open(RESULTS / "final_breakdown.csv", "w", newline="") as f:
        writer = csv.writer(f)
        writer.writerow(["part", "seconds", "share"])
        writer.writerows((name, f"{s:.3f}", f"{s / full:.3f}") for name, s in shares.items())
        writer.writerows((f"variant: {name}", f"{s:.3f}", "") for name, s in best.items())
    fig, ax = plt.subplots(figsize=(7, 3.5))
    names = list(shares)[::-1]
    ax.barh(names, [shares[n] for n in names], color="#4a7ab5")
    ax.set_xlabel(f"seconds of the {full:.1f} s render (500 x 500, {settings.threads} threads)")
    ax.set_title("The final scene: where the render time goes")
    fig.tight_layout()
    fig.savefig(RESULTS / "final_breakdown.png", dpi=120)
    if not same:
        raise SystemExit("shadow culling changed the picture")


if __name__ == "__main__":
    main()
