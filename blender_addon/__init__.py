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


def _import_as_core(folder: Path) -> None:
    spec = importlib.util.spec_from_file_location(
        "core", folder / "__init__.py", submodule_search_locations=[str(folder)]
    )
    module = importlib.util.module_from_spec(spec)
    sys.modules["core"] = module
    spec.loader.exec_module(module)


def _make_core_importable() -> None:
    """Find `core` and its packages: in the zip a user installed (`core` inside the add-on,
    numba and Pillow as the extension's wheels), or from a link into Blender's add-ons
    folder to `blender_addon/` in a Whitted checkout (`core` beside it, numpy and numba in
    the checkout's `.venv`). Paths are appended to sys.path, after Blender's own modules, so
    Blender's bpy and numpy win.
    """
    here = Path(__file__).resolve().parent
    checkout = here.parent
    own_core = here / "core"
    if own_core.is_dir():
        # An installed zip carries `core` inside the add-on: that one, which its shipped
        # kernels were compiled from, even where another package of that common name can be
        # imported (an editable install of a checkout, say)
        if str(here) not in sys.path:
            sys.path.append(str(here))
        found = importlib.util.find_spec("core")
        if found is None or not found.origin or Path(found.origin).resolve().parent != own_core:
            _import_as_core(own_core)  # ahead of a `core` earlier on sys.path
    elif importlib.util.find_spec("core") is None:
        sys.path.append(str(checkout))
    if importlib.util.find_spec("numba") is None:
        version = f"python{sys.version_info[0]}.{sys.version_info[1]}"
        site = checkout / ".venv" / "lib" / version / "site-packages"
        if site.is_dir():
            sys.path.append(str(site))


_make_core_importable()

from . import engine, kernel_status, lua_import, operators, properties, ui  # noqa: E402

_modules = (properties, engine, operators, lua_import, ui, kernel_status)


def register():
    for module in _modules:
        module.register()


def unregister():
    for module in reversed(_modules):
        module.unregister()
