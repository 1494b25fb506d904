"""Whitted: an exact recursive ray tracer as a Blender render engine.

Loaded by Blender 4.2+ as an extension (blender_manifest.toml) and by Blender 3.4 to 4.1 as
a legacy add-on (bl_info) named `whitted`. The renderer itself is the Blender-free `core`
package, this add-on's subpackage.
"""

import importlib.util
import os
import sys
from pathlib import Path

bl_info = {
    "name": "Whitted",
    "author": "Whitted developers",
    "version": (0, 1, 0),
    "blender": (3, 4, 0),
    "location": "Render Properties > Render Engine > Whitted",
    "description": "Exact recursive ray tracer: analytic shapes, Phong shading, hard shadows",
    "category": "Render",
}


def _share_checkout_core(core_module) -> None:
    """Serve the checkout's top-level `core`, already importable, as this add-on's `.core`,
    each of its modules under both names: one copy of the renderer in the process (tests,
    `make render`), whose kernels load from the checkout's one cache."""
    import pkgutil

    prefix = f"{__name__}.core"
    sys.modules[prefix] = core_module
    for found in pkgutil.walk_packages(core_module.__path__, "core."):
        if found.name.endswith("__main__"):  # the command line: running it would render
            continue
        if found.name.startswith("core.farm."):  # the farm command's, some needing Dask's
            continue  # `distributed`, which Blender's Python need not have: never run here
        module = importlib.import_module(found.name)
        sys.modules[prefix + found.name[len("core") :]] = module


def _make_core_importable() -> None:
    """Make the renderer importable as this add-on's subpackage `.core`, never as a top-level
    `core`, a name another add-on may well use (Blender shares one sys.path between add-ons).
    In the zip a user installs, `core` is inside the add-on (numba and Pillow come as the
    extension's wheels): nothing to do. From a link into Blender's add-ons folder to
    `blender_addon/` in a Whitted checkout, `core` is beside it (numpy and numba in the
    checkout's `.venv`): the package's search path takes in the checkout, unless that same
    `core` is importable already. Paths are appended to sys.path, after Blender's own
    modules, so Blender's bpy and numpy win.
    """
    here = Path(__file__).resolve().parent
    checkout = here.parent
    if not (here / "core").is_dir() and (checkout / "core").is_dir():
        found = importlib.util.find_spec("core")
        if found and found.origin and Path(found.origin).resolve().parent == checkout / "core":
            _share_checkout_core(importlib.import_module("core"))
        else:
            __path__.append(str(checkout))
    if importlib.util.find_spec("numba") is None:
        version = f"python{sys.version_info[0]}.{sys.version_info[1]}"
        site = checkout / ".venv" / "lib" / version / "site-packages"
        if site.is_dir():
            sys.path.append(str(site))


def _choose_kernel_cache() -> None:
    """Where compiled kernels are kept, unless WHITTED_CACHE_DIR says (a farm's shared
    folder, say): installed, in the folder Blender gives an extension for its user data, kept
    across updates; from a checkout, in the checkout's `.cache/kernels`, which its tests
    share. Read by core.jit.cache_folder on import, and passed on to the warm-up process."""
    if os.environ.get("WHITTED_CACHE_DIR"):
        return
    here = Path(__file__).resolve().parent
    if (here / "core").is_dir():
        import bpy

        if __package__.startswith("bl_ext.") and hasattr(bpy.utils, "extension_path_user"):
            folder = bpy.utils.extension_path_user(__package__, path="kernel_cache", create=True)
            os.environ["WHITTED_CACHE_DIR"] = folder
    elif (here.parent / "core").is_dir():
        os.environ["WHITTED_CACHE_DIR"] = str(here.parent / ".cache" / "kernels")


_choose_kernel_cache()
_make_core_importable()

from . import engine, lua, properties, ui  # noqa: E402
from .engine import kernel_status  # noqa: E402

# Settings first (the engine and panels read them); the kernel warm-up last
_modules = (properties, engine, lua, ui, kernel_status)


def register():
    for module in _modules:
        module.register()


def unregister():
    for module in reversed(_modules):
        module.unregister()
