"""Material previews in Blender 3.4's real window (under Xvfb) render with Whitted: the
refraction sample's diffuse walls, its checker texture and its glass ball, and a pink node
material, each get a thumbnail, made by Whitted's engine (its preview renders counted), that
shows the material in its colour."""

import json
import os
import shutil
import subprocess
import sys

import numpy as np
import pytest

from tests.support import ROOT

pytestmark = pytest.mark.blender34

DRIVER = ROOT / "tests" / "blender" / "scripts" / "window_previews.py"
SAMPLE = ROOT / "sample_blends" / "refraction.blend"


def test_material_previews_render_with_whitted(display, tmp_path):
    out = tmp_path / "previews.json"
    site = ROOT / ".venv" / "lib" / "python3.11" / "site-packages"
    if not site.is_dir():
        site = next(p for p in sys.path if p.endswith("site-packages"))
    env = dict(os.environ, DISPLAY=display, PYTHONPATH=f"{ROOT}{os.pathsep}{site}")
    run = subprocess.run(
        [shutil.which("blender"), "--python-use-system-env", "--addons", "whitted",
         str(SAMPLE), "--python", str(DRIVER), "--", str(out)],
        env=env, capture_output=True, text=True, timeout=300,
    )  # fmt: skip
    assert out.is_file(), run.stdout[-3000:] + run.stderr[-3000:]
    seen = json.loads(out.read_text())
    previews = {name: np.array(rows) for name, rows in seen["materials"].items()}
    assert sorted(previews) == ["Blue Wall", "Checker", "Glass", "Pink", "Red Wall"]
    assert seen["previews rendered by Whitted"] >= len(previews)
    for name, pixels in previews.items():
        assert pixels.shape == (128, 128, 3), name
        assert (pixels.max(axis=2) > 0.02).mean() > 0.5, f"{name}: the thumbnail is blank"
    # The preview ball fills the middle of the thumbnail: its colour is the material's
    ball = {name: pixels[40:88, 40:88] for name, pixels in previews.items()}
    red, green, blue = ball["Red Wall"].mean(axis=(0, 1))
    assert red > 2 * blue and red > 2 * green
    red, green, blue = ball["Blue Wall"].mean(axis=(0, 1))
    assert blue > 2 * red and blue > 1.5 * green
    # A node material in the colour its Principled BSDF was given, under the preview's bright
    # lights (displayed: 1, 0.58, 0.77 for linear 1, 0.3, 0.55): red over blue over green
    red, green, blue = ball["Pink"].mean(axis=(0, 1))
    assert red > 1.1 * blue and blue > 1.15 * green, (red, green, blue)
    # The checker texture: dark and light squares both cover a good part of the ball
    brightness = ball["Checker"].mean(axis=2)
    assert (brightness < 0.3 * brightness.max()).mean() > 0.15
    assert (brightness > 0.7 * brightness.max()).mean() > 0.15
    # Glass lets the grey backdrop through: the ball is as neutral as the backdrop
    glass = ball["Glass"].mean(axis=(0, 1))
    assert np.ptp(glass) < 0.05 * glass.max()
    assert "Traceback" not in run.stdout + run.stderr, run.stderr[-3000:]
