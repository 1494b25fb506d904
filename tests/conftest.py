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


def pytest_collection_modifyitems(items):
    """Tests marked `first` run before all others, in their order: a cold compile of the
    add-on's kernels that, in a new checkout, leaves its cache as the shared one, before any
    other test compiles them again (tests/blender/test_blender34_cli.py)."""
    items.sort(key=lambda item: item.get_closest_marker("first") is None)
