"""A new user's first picture: `blender -b` from an empty kernel cache to the saved frame.

Three scenes, each rendered as a farm or `make render` renders it (whole process: Blender's
start, the add-on, the kernel warm-up, the render, the PNG written), from an empty cache:
  - the report's final scene (sample_blends/final_scene.blend),
  - a node-material scene (a noise-textured Principled BSDF under a Layer Weight coat, an
    area light and the World),
  - a caustics scene (a Glass BSDF ball on a plane under the sun, caustics on).
Each from an empty cache with the kernel variant the scene needs (core.jit.variants), and
with the full kernel (WHITTED_FULL_KERNEL=1, which warms and renders everything as before
the variants), interleaved; then, the caches filled, warm renders of both, interleaved.

Prints, as `name: value` lines (seconds, medians of the rounds):
  cold_<scene>_variant_s, cold_<scene>_full_s   empty cache to the saved frame
  cold_<scene>_ratio                             variant / full
  compile_<scene>_variant_s, compile_<scene>_full_s   the warm-up's own seconds
  warm_<scene>_variant_s, warm_<scene>_full_s   the cache filled
  warm_<scene>_ratio                             variant / full
Writes results/cold_render.png and cold_render.csv.
"""

import csv
import os
import re
import statistics
import subprocess
import tempfile
import time
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

ROOT = Path(__file__).resolve().parents[2]
RESULTS = Path(__file__).resolve().parent / "results"
SITE = ROOT / ".venv" / "lib" / "python3.11" / "site-packages"
ROUNDS = int(os.environ.get("WHITTED_BENCH_ROUNDS", "2"))
READY = re.compile(r"kernels ready in (?P<seconds>[\d.]+) s")

# Built in Blender and saved: a node material that varies over the surface, and a caustic
BUILD = """
import bpy, sys
kind, path = sys.argv[-2], sys.argv[-1]
scene = bpy.context.scene
scene.render.engine = "WHITTED"
scene.render.resolution_x, scene.render.resolution_y = 480, 270
scene.render.resolution_percentage = 100
cube = bpy.data.objects["Cube"]
material = bpy.data.materials.new(kind)
material.use_nodes = True
tree = material.node_tree
principled = tree.nodes["Principled BSDF"]
if kind == "nodes":
    noise = tree.nodes.new("ShaderNodeTexNoise")
    tree.links.new(noise.outputs["Color"], principled.inputs["Base Color"])
    weight = tree.nodes.new("ShaderNodeLayerWeight")
    glossy = tree.nodes.new("ShaderNodeBsdfGlossy")
    mix = tree.nodes.new("ShaderNodeMixShader")
    tree.links.new(weight.outputs["Fresnel"], mix.inputs["Fac"])
    tree.links.new(principled.outputs["BSDF"], mix.inputs[1])
    tree.links.new(glossy.outputs["BSDF"], mix.inputs[2])
    tree.links.new(mix.outputs["Shader"], tree.nodes["Material Output"].inputs["Surface"])
    light = bpy.data.objects["Light"]
    light.data.type = "AREA"
    light.data.energy = 800.0
else:
    bpy.data.objects.remove(cube)
    bpy.ops.mesh.primitive_uv_sphere_add(radius=1.0, location=(0.0, 0.0, 1.0))
    cube = bpy.context.active_object
    bpy.ops.object.shade_smooth()
    glass = tree.nodes.new("ShaderNodeBsdfGlass")
    tree.links.new(glass.outputs["BSDF"], tree.nodes["Material Output"].inputs["Surface"])
    bpy.ops.mesh.primitive_plane_add(size=20.0)
    bpy.data.objects["Light"].data.type = "SUN"
    bpy.data.objects["Light"].data.energy = 3.0
cube.data.materials.clear()
cube.data.materials.append(material)
bpy.ops.wm.save_as_mainfile(filepath=path)
"""


def environment(cache: Path, full: bool) -> dict:
    return {
        **os.environ,
        "PYTHONPATH": f"{ROOT}:{SITE}",
        "WHITTED_CACHE_DIR": str(cache),
        "BLENDER_USER_SCRIPTS": str(ROOT / ".build" / "blender_scripts"),
        "WHITTED_FULL_KERNEL": "1" if full else "0",
    }


def blender(*arguments, cache: Path, full: bool):
    env = environment(cache, full)
    command = ["blender", "-b", "--python-use-system-env", "--addons", "whitted", *arguments]
    start = time.perf_counter()
    run = subprocess.run(command, env=env, capture_output=True, text=True, timeout=1800)
    seconds = time.perf_counter() - start
    if run.returncode != 0 or "Saved:" not in run.stdout:
        raise RuntimeError(f"blender failed: {run.stdout[-2000:]}{run.stderr[-2000:]}")
    ready = READY.search(run.stdout)
    return seconds, float(ready["seconds"]) if ready else 0.0


def build_scene(kind: str, folder: Path) -> Path:
    path = folder / f"{kind}.blend"
    subprocess.run(["blender", "-b", "--factory-startup", "--python-use-system-env", "--addons",
                    "whitted", "--python-exit-code", "1", "--python-expr", BUILD, "--", kind,
                    str(path)], check=True, capture_output=True, timeout=300,
                   env=environment(folder / "build_cache", False))  # fmt: skip
    return path


def main():
    with tempfile.TemporaryDirectory() as temporary:
        folder = Path(temporary)
        scenes = {
            "final_scene": ROOT / "sample_blends" / "final_scene.blend",
            "nodes": build_scene("nodes", folder),
            "caustics": build_scene("caustics", folder),
        }
        rows = []
        for name, path in scenes.items():
            frame = ["-o", str(folder / f"{name}_####"), "-F", "PNG", "-f", "1"]
            times = {(kind, mode): [] for kind in ("cold", "compile", "warm")
                     for mode in ("variant", "full")}  # fmt: skip
            for round_ in range(ROUNDS):
                for mode in ("variant", "full") if round_ % 2 == 0 else ("full", "variant"):
                    cache = folder / f"cache_{name}_{mode}_{round_}"
                    seconds, compile_s = blender(str(path), "-E", "WHITTED", *frame,
                                                 cache=cache, full=mode == "full")  # fmt: skip
                    times["cold", mode].append(seconds)
                    times["compile", mode].append(compile_s)
            for round_ in range(ROUNDS):
                for mode in ("variant", "full") if round_ % 2 == 0 else ("full", "variant"):
                    cache = folder / f"cache_{name}_{mode}_0"
                    seconds, _ = blender(str(path), "-E", "WHITTED", *frame, cache=cache,
                                         full=mode == "full")  # fmt: skip
                    times["warm", mode].append(seconds)
            for kind in ("cold", "compile", "warm"):
                for mode in ("variant", "full"):
                    value = statistics.median(times[kind, mode])
                    print(f"{kind}_{name}_{mode}_s: {value:.1f}", flush=True)
                    rows.append((name, kind, mode, value))
                if kind != "compile":
                    ratio = statistics.median(times[kind, "variant"]) / statistics.median(
                        times[kind, "full"]
                    )
                    print(f"{kind}_{name}_ratio: {ratio:.2f}", flush=True)
    RESULTS.mkdir(exist_ok=True)
    with open(RESULTS / "cold_render.csv", "w", newline="") as out:
        csv.writer(out).writerows([("scene", "measure", "kernel", "seconds"), *rows])
    chart(rows)


def chart(rows):
    names = list(dict.fromkeys(name for name, *_ in rows))
    figure, axes = plt.subplots(figsize=(7, 4))
    width = 0.2
    for k, (kind, mode) in enumerate([("cold", "full"), ("cold", "variant"),
                                      ("warm", "full"), ("warm", "variant")]):  # fmt: skip
        values = [next(v for n, kd, m, v in rows if (n, kd, m) == (name, kind, mode))
                  for name in names]  # fmt: skip
        axes.bar([i + (k - 1.5) * width for i in range(len(names))], values, width,
                 label=f"{kind}, {mode} kernel")  # fmt: skip
    axes.axhline(30, color="grey", linestyle=":", linewidth=1)
    axes.set_xticks(range(len(names)), names)
    axes.set_ylabel("blender -b to the saved frame (s)")
    axes.set_title("First picture from an empty kernel cache, and warm")
    top = max(value for *_, value in rows)
    axes.set_ylim(0, top * 1.4)  # room for the legend above the bars
    axes.legend(ncol=2, loc="upper center")
    figure.tight_layout()
    figure.savefig(RESULTS / "cold_render.png", dpi=120)


if __name__ == "__main__":
    main()
