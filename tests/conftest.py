"""Shared set-up: one numba kernel cache for every test process and Blender subprocess, and
the add-on link Blender loads `whitted` from. Runs before any test module imports core."""

import os
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
os.environ.setdefault("WHITTED_CACHE_DIR", str(ROOT / ".cache" / "kernels"))
os.environ.setdefault("BLENDER_USER_SCRIPTS", str(ROOT / ".build" / "blender_scripts"))

_addon_link = Path(os.environ["BLENDER_USER_SCRIPTS"]) / "addons" / "whitted"
if not _addon_link.exists():
    _addon_link.parent.mkdir(parents=True, exist_ok=True)
    _addon_link.symlink_to(ROOT / "blender_addon", target_is_directory=True)
