"""First pixel: how long a new user waits, with an empty kernel cache and with a filled one.

Prints, as `name: value` lines:
  kernel_cold_compile_s        the kernel warm-up (everything a render needs) in a new
                               process with a new cache folder
  kernel_compile_<step>_s      where that time went, step by step
  first_pixel_cold_s           process start to the final scene's first tile, new cache
                               (imports, warm-up, export of the pickled scene, first tile)
  first_pixel_cached_s         the same with the cache the cold run filled
  first_pixel_installed_s      the same from the unpacked extension zip (`make addon`) with
                               a new user cache: the kernels it ships are copied, not compiled
  kernel_recompiles_across_scenes   new processes, one shared cache filled by the warm-up:
                               how many of the scenes (every kind, and the final scene)
                               compiled anything at render time; must be 0
Writes results/first_pixel.png and first_pixel.csv.
"""

import csv
import os
import pickle
import re
import subprocess
import sys
import tempfile
import zipfile
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from blender_addon.packaging.build_extension import build  # noqa: E402
from core.jit.decorators import CPU_TARGET  # noqa: E402
from tests.benchmarks.final_scene_data import final_scene  # noqa: E402

ROOT = Path(__file__).resolve().parents[2]
RESULTS = Path(__file__).resolve().parent / "results"
READY = re.compile(r"kernels ready in (?P<total>[\d.]+) s \((?P<steps>.*)\)")

# A new process: warm-up if the cache is not complete, then the final scene at 100 x 100 up
# to its first tile; prints the warm-up's lines and the seconds from process start
FIRST_PIXEL = """
import time
start = time.perf_counter()
import dataclasses, pickle, sys
from core.jit.warmup import kernels_ready, warm_kernels
from core.driver import render
if not kernels_ready():
    warm_kernels()
scene, settings = pickle.load(open(sys.argv[1], "rb"))
settings = dataclasses.replace(settings, width=100, height=100, tile_size=16)
first = []
def on_tile(*args):
    if not first:
        first.append(time.perf_counter() - start)
out = render(scene, settings, on_tile=on_tile)
print(f"first_pixel {first[0]:.3f} kernels {out.stats.kernel_source}")
"""

# The same from the unpacked zip, its `core` imported under the name Blender gives it (the
# kernels it ships are compiled for that name: a `core` imported as `core` would find none),
# its parents bare packages (the add-on's own __init__ needs bpy); also says what it shipped
INSTALLED = "bl_ext.user_default.whitted.core"
INSTALLED_FIRST_PIXEL = f"""
import time
start = time.perf_counter()
import dataclasses, importlib, pickle, sys, types
folder = sys.argv[2]
for name, path in (("bl_ext", []), ("bl_ext.user_default", []),
                   ("bl_ext.user_default.whitted", [folder])):
    package = types.ModuleType(name)
    package.__path__ = path
    sys.modules[name] = package
warmup = importlib.import_module("{INSTALLED}.jit.warmup")
shipped = importlib.import_module("{INSTALLED}.jit.cache_folder").shipped_kernels()
found = sorted(p.name for p in shipped.glob("warm-*.ok")) if shipped.is_dir() else []
print(f"shipped {{shipped.name if shipped.is_dir() else 'none'}} {{','.join(found) or '-'}} "
      f"wanted {{warmup.MARKER}}")
kernels_ready, warm_kernels = warmup.kernels_ready, warmup.warm_kernels
render = importlib.import_module("{INSTALLED}.driver").render

class Installed(pickle.Unpickler):
    def find_class(self, module, name):
        if module == "core" or module.startswith("core."):
            module = "{INSTALLED[:-4]}" + module
        return super().find_class(module, name)
""" + FIRST_PIXEL.split("from core.driver import render", 1)[1].replace(
    'pickle.load(open(sys.argv[1], "rb"))', 'Installed(open(sys.argv[1], "rb")).load()'
).replace("from core.jit.warmup import kernels_ready, warm_kernels\n", "")

SCENE_SOURCE = """
import pickle, sys
from core import RenderSettings, render
from tests.support.scenes import one_of_each_kind as scenes
name = sys.argv[1]
if name == "final scene":
    scene, _ = pickle.load(open(sys.argv[2], "rb"))
else:
    scene = scenes()[name]
print(render(scene, RenderSettings(8, 8, pixel_samples=1)).stats.kernel_source)
"""


def python(code, cache, *args, cwd=ROOT):
    env = {**os.environ, "WHITTED_CACHE_DIR": str(cache)}
    done = subprocess.run([sys.executable, "-c", code, *args], cwd=cwd, env=env,
                          capture_output=True, text=True, check=True)  # fmt: skip
    return done.stdout


def first_pixel(cache, scene_file, installed=None):
    if installed is None:
        out = python(FIRST_PIXEL, cache, str(scene_file))
    else:
        out = python(INSTALLED_FIRST_PIXEL, cache, str(scene_file), str(installed))
    seconds, source = re.search(r"first_pixel ([\d.]+) kernels (\w+)", out).groups()
    ready = READY.search(out)
    shipped = re.search(r"shipped (\S+) (\S+) wanted (\S+)", out)
    return float(seconds), source, ready, shipped


def main():
    from tests.support.scenes import one_of_each_kind as scenes

    with tempfile.TemporaryDirectory() as folder:
        cache, scene_file = Path(folder) / "cache", Path(folder) / "final.pkl"
        scene_file.write_bytes(pickle.dumps(final_scene()))
        cold, cold_source, ready, _ = first_pixel(cache, scene_file)
        cached, cached_source, _, _ = first_pixel(cache, scene_file)
        # The extension as Blender unpacks it; its `core` comes first on the path (the
        # working folder), before the checkout's
        installed_folder = Path(folder) / "installed"
        zip_path = build(
            Path(folder) / "dist", False, kernel_cache=cache, levels=(CPU_TARGET,),
            platforms=("linux-x64",),
        )["linux-x64"]  # fmt: skip
        zipfile.ZipFile(zip_path).extractall(installed_folder)
        installed, installed_source, compiled, shipped = first_pixel(
            Path(folder) / "new_user_cache", scene_file, installed_folder
        )
        names = [*scenes(), "final scene"]
        sources = {n: python(SCENE_SOURCE, cache, n, str(scene_file)).split()[-1] for n in names}
    steps = [(s.rsplit(" ", 2)[0], float(s.rsplit(" ", 2)[1])) for s in ready["steps"].split(", ")]
    print(f"kernel_cold_compile_s: {float(ready['total']):.1f}")
    for label, seconds in steps:
        print(f"kernel_compile_{label.replace(' ', '_')}_s: {seconds:.1f}")
    print(f"first_pixel_cold_s: {cold:.1f}")
    print(f"first_pixel_cached_s: {cached:.2f} (kernels from the {cached_source})")
    print(
        f"first_pixel_installed_s: {installed:.2f} (kernels from the {installed_source}"
        + (f"; compiled! {why_not_shipped(shipped)}" if compiled else ", shipped")
        + ")"
    )
    recompiled = [n for n, s in sources.items() if s != "cache"]
    print(
        f"kernel_recompiles_across_scenes: {len(recompiled)}"
        + (f" {recompiled}" * bool(recompiled))
    )
    write_results(steps, cold, cached, installed)


def why_not_shipped(shipped) -> str:
    """Why the installed zip's kernels were not used, from what the installed run saw."""
    if shipped is None:
        return "(the installed run said nothing of its shipped kernels)"
    folder, markers, wanted = shipped.groups()
    if folder == "none":
        return "(the zip holds no kernels for this core's cache folder: built for another name?)"
    if wanted not in markers.split(","):
        return f"(the zip ships {markers}; this CPU compiles for {wanted[5:-3]})"
    return f"(the zip ships {wanted}, yet its kernels did not load: numba's key differs)"


def write_results(steps, cold, cached, installed):
    RESULTS.mkdir(exist_ok=True)
    with open(RESULTS / "first_pixel.csv", "w", newline="") as f:
        writer = csv.writer(f)
        writer.writerow(["figure", "seconds"])
        writer.writerows([(f"compile: {label}", s) for label, s in steps])
        writer.writerows([("first pixel, new cache", cold), ("first pixel, cached", cached),
                          ("first pixel, new install", installed)])  # fmt: skip
    fig, (left, right) = plt.subplots(1, 2, figsize=(10, 3.6))
    left.barh([label for label, _ in steps][::-1], [s for _, s in steps][::-1], color="tab:blue")
    left.set_xlabel("seconds")
    left.set_title("Cold compile, step by step")
    right.bar(["new cache", "cached", "new install\n(shipped kernels)"], [cold, cached, installed],
              color=["tab:red", "tab:green", "tab:olive"])  # fmt: skip
    right.set_yscale("log")
    right.set_ylabel("seconds, process start to first tile (log)")
    right.set_title("First pixel of the final scene")
    fig.tight_layout()
    fig.savefig(RESULTS / "first_pixel.png", dpi=110)


if __name__ == "__main__":
    main()
