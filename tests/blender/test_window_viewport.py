"""Rendered shading in Blender 3.4's real window (under Xvfb): the 3D view, switched to
Rendered through the scene camera, shows Whitted's picture; a moved ball moves in it (read
back from screenshots of the window); the move re-exports the scene but no mesh; switching to
Solid stops the render thread."""

import json
import os
import shutil
import subprocess
import sys

import numpy as np
import pytest
from PIL import Image

from tests.blender.test_window_previews import WINDOW_TIMEOUT_S
from tests.support import ROOT

pytestmark = pytest.mark.blender34

DRIVER = ROOT / "tests" / "blender" / "scripts" / "window_viewport.py"
SPHERES = ROOT / "sample_blends" / "spheres.blend"


def blue_ball(path):
    """Centre (x, y) and pixel count of the blue ball in a window screenshot: the pixels much
    bluer than red and green, inside the 3D view (left of its navigation gizmo)."""
    pixels = np.asarray(Image.open(path).convert("RGB"), float)[100:700, 60:950]
    blue = (pixels[..., 2] > pixels[..., 0] + 60) & (pixels[..., 2] > pixels[..., 1] + 60)
    ys, xs = np.nonzero(blue)
    return xs.mean(), ys.mean(), int(blue.sum())


def test_rendered_shading_shows_the_scene_and_follows_a_moved_object(display, tmp_path):
    out = tmp_path / "seen.json"
    site = ROOT / ".venv" / "lib" / "python3.11" / "site-packages"
    if not site.is_dir():
        site = next(p for p in sys.path if p.endswith("site-packages"))
    env = dict(os.environ, DISPLAY=display, PYTHONPATH=f"{ROOT}{os.pathsep}{site}")
    run = subprocess.run(
        [shutil.which("blender"), "--python-use-system-env", "--addons", "whitted",
         str(SPHERES), "--python", str(DRIVER), "--", str(out)],
        env=env, capture_output=True, text=True, timeout=WINDOW_TIMEOUT_S,
    )  # fmt: skip
    assert out.is_file(), run.stdout[-3000:] + run.stderr[-3000:]
    seen = json.loads(out.read_text())
    assert seen["status"] == "Whitted | Done | pass 5/5", seen
    # moving an object re-exports the scene once; its spheres are exact shapes, no mesh is read
    exports, reframes, conversions = seen["counts before"]
    assert seen["counts after"] == [exports + 1, reframes, conversions], seen
    before_x, before_y, before_count = blue_ball(f"{out}.before.png")
    after_x, after_y, after_count = blue_ball(f"{out}.after.png")
    assert before_count > 2000  # the ball is drawn: the viewport shows Whitted's picture
    # 1 m along +x: to the right in the camera's view, and nearer (larger, lower)
    assert after_x > before_x + 10, (before_x, after_x)
    assert after_count > before_count
    # Solid shading freed the engine: its render thread stopped, no session is left
    assert not seen["render thread alive"] and seen["sessions left"] == 0, seen
    assert "whitted-progressive" not in " ".join(seen["threads"])
    assert "Traceback" not in run.stdout + run.stderr, run.stderr[-3000:]
