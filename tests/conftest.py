"""Shared set-up: one numba kernel cache for every test process and Blender subprocess, and
the add-on link Blender loads `whitted` from. Runs before any test module imports core."""

import os
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
os.environ.setdefault("WHITTED_CACHE_DIR", str(ROOT / ".cache" / "kernels"))
os.environ.setdefault("BLENDER_USER_SCRIPTS", str(ROOT / ".build" / "blender_scripts"))
# Every render by the full kernel (core.jit.variants), which one warm-up compiles for all the
# suite's scenes: by the variant each scene needs, the suite's hundreds of scenes would
# compile dozens of variants. The variants are tested where they are asked for by name
# (tests/core/test_kernel_variants.py, the Blender 3.4 render of a variant from an empty
# cache in tests/blender/test_blender34_cli.py, make bench's bench_cold_render).
os.environ.setdefault("WHITTED_FULL_KERNEL", "1")

_addon_link = Path(os.environ["BLENDER_USER_SCRIPTS"]) / "addons" / "whitted"
if not _addon_link.exists():
    _addon_link.parent.mkdir(parents=True, exist_ok=True)
    _addon_link.symlink_to(ROOT / "blender_addon", target_is_directory=True)


def pytest_collection_modifyitems(items):
    """Tests marked `first` run before all others, in their order: cold compiles that, in a
    new checkout, leave their caches as the shared one's, before any other test compiles the
    same kernels again (the add-on's in tests/blender/test_blender34_cli.py, core's in
    tests/core/kernels/test_kernel_signature.py; tests/support/seed_cache.py)."""
    items.sort(key=lambda item: item.get_closest_marker("first") is None)
