"""The report's final scene as the add-on exports it: `sample_blends/final_scene.blend` read by
the bpy module in a subprocess and converted by `blender_addon.export.convert`, so the
benchmarks that need the scene itself (to write it for POV-Ray, or to render variants of it
in-process) use exactly what `blender -b` renders."""

import os
import pickle
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
SCENE = ROOT / "sample_blends" / "final_scene.blend"

_EXPORT = """
import pickle, sys
import bpy  # first: it makes addon_utils importable
import addon_utils
addon_utils.enable("whitted", default_set=True, handle_error=None)
bpy.ops.wm.open_mainfile(filepath=sys.argv[1])
from blender_addon import export
from tests.support.render_view import export_scenes
_, scene, settings = export_scenes(bpy, export)[0]
with open(sys.argv[2], "wb") as f:
    pickle.dump((scene, settings), f)
"""


def final_scene(path: Path = SCENE):
    """(core.Scene, core.RenderSettings) of a .blend file, as Whitted's exporter makes them."""
    env = dict(os.environ)
    env["BLENDER_USER_SCRIPTS"] = str(ROOT / ".build" / "blender_scripts")
    env["PYTHONPATH"] = str(ROOT)
    with tempfile.TemporaryDirectory() as folder:
        out = Path(folder) / "scene.pickle"
        done = subprocess.run([sys.executable, "-c", _EXPORT, str(path), str(out)], env=env,
                              capture_output=True, text=True, cwd=ROOT)  # fmt: skip
        if done.returncode != 0 or not out.exists():
            sys.exit(f"exporting {path.name} failed:\n{done.stdout[-2000:]}{done.stderr[-2000:]}")
        with open(out, "rb") as f:
            return pickle.load(f)
