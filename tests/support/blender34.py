"""Running Debian's Blender 3.4 (a real `blender -b`) as `make render` does."""

import os
import shutil
import subprocess
import sys

from tests.support import ROOT


def blender_34(*args, timeout=300):
    """Run `blender -b` the way `make render` does: add-on from BLENDER_USER_SCRIPTS, numpy
    and numba from the project's virtual environment."""
    blender = shutil.which("blender")
    assert blender, "no `blender` on PATH: run `make test`, which installs Debian's package"
    site = ROOT / ".venv" / "lib" / "python3.11" / "site-packages"
    if not site.is_dir():  # running from some other environment: use its packages
        site = next(p for p in sys.path if p.endswith("site-packages"))
    env = dict(os.environ, PYTHONPATH=f"{ROOT}{os.pathsep}{site}")
    command = [blender, "-b", "--python-use-system-env", *args]
    return subprocess.run(command, env=env, capture_output=True, text=True, timeout=timeout)
