"""Whitted: an exact recursive ray tracer as a Blender render engine.

Loaded by Blender as a legacy add-on (bl_info) named `whitted`; Blender 3.4 and 5.0 are
supported. The renderer itself is the Blender-free `core` package next to this folder.
"""

import importlib.util
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


def _make_core_importable() -> None:
    """Find `core` and its packages when Blender loads us from a link into its add-ons folder.

    The add-on folder is normally a symbolic link to `blender_addon/` in a Whitted checkout:
    `core` sits next to it, and `make` puts numpy and numba in the checkout's `.venv`. Both
    are appended to sys.path, after Blender's own modules, so Blender's bpy and numpy win.
    """
    checkout = Path(__file__).resolve().parent.parent
    if importlib.util.find_spec("core") is None and (checkout / "core").is_dir():
        sys.path.append(str(checkout))
    if importlib.util.find_spec("numba") is None:
        version = f"python{sys.version_info[0]}.{sys.version_info[1]}"
        site = checkout / ".venv" / "lib" / version / "site-packages"
        if site.is_dir():
            sys.path.append(str(site))


_make_core_importable()

from . import engine, operators, properties, ui  # noqa: E402  (needs core on sys.path first)

_modules = (properties, engine, operators, ui)


def register():
    for module in _modules:
        module.register()


def unregister():
    for module in reversed(_modules):
        module.unregister()
