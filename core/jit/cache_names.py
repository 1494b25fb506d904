"""One kernel cache for every name `core` is imported under: `core` in a checkout,
`whitted.core` as Blender 3.4's add-on, `bl_ext.user_default.whitted.core` as an extension.

numba's cache files name the modules their kernels came from, by import name: the classes
of the arrays' named tuples (`core.kernels.layout.PackedScene`), the module whose globals a
kernel's environment holds, and the module its function descriptor imports when the
kernel is loaded. A cache compiled under one name therefore failed to load under another
(the named tuple types differ, so no signature matched), and each name compiled the same
kernels again: the suite compiled them three times per Python and numba (a checkout's
tests, Blender 3.4's add-on, the extension's zip), and the zip's kernels came from a
compile of their own.

Here numba's reading of index and data files, in Whitted's cache folders only, maps a
module name under another Whitted core (`<prefix>core.<our module>`) to the same module
under this one. Nothing else in the files depends on the name: the machine code's symbols
are named after the package that compiled it, but they are only names, consistent within
the cached library, and the source stamps and CPU target are numba's own checks as before.
Two cores in one process are the exception (core.jit.cache_folder): there the second keeps
a folder of its own, so that no function is defined twice under one symbol.
"""

from __future__ import annotations

import functools
import io
import pickle
from pathlib import Path

from .relocatable import CORE

# This core's import name
OWN_PACKAGE = __package__.rpartition(".")[0]
# Packages of that last name that are never a Whitted core (numba's own is `numba.core`)
NOT_OURS = ("numba", "llvmlite", "numpy")


@functools.cache
def _is_own_module(inside: str) -> bool:
    """Whether `inside` (`kernels.layout`) names a module or package of this core: a test's
    `tests.core.kernels.test_shapes`, cached beside ours, names none and is left alone."""
    path = CORE.joinpath(*inside.split("."))
    return path.with_suffix(".py").is_file() or (path / "__init__.py").is_file()


def own_module_name(name: str) -> str:
    """`name` as this core calls it, if it names a module of some Whitted core."""
    package, dot, rest = name.partition(".core.")
    if dot:
        package += ".core"
    elif name.startswith("core."):
        package, rest = "core", name[len("core.") :]
    else:
        return name
    if package == OWN_PACKAGE or package.split(".")[0] in NOT_OURS:
        return name
    if not _is_own_module(rest):
        return name
    return f"{OWN_PACKAGE}.{rest}"


class _OwnNamesUnpickler(pickle.Unpickler):
    def find_class(self, module: str, name: str):
        if (module, name) == ("numba.core.environment", "_rebuild_env"):
            return _rebuild_env_here
        return super().find_class(own_module_name(module), name)


def _rebuild_env_here(modname, consts, env_name):
    from numba.core.environment import _rebuild_env

    return _rebuild_env(own_module_name(modname), consts, env_name)


def loads(data: bytes):
    """pickle.loads, with every Whitted core's module names read as this core's."""
    return _OwnNamesUnpickler(io.BytesIO(data)).load()


def _own_descriptor(loaded) -> None:
    """The loaded kernel's function descriptor imports its module by this core's name."""
    from numba.core.funcdesc import FunctionDescriptor

    for part in loaded if isinstance(loaded, tuple) else ():
        if isinstance(part, FunctionDescriptor):
            part.modname = own_module_name(part.modname)


def read_any_core_names(folders: list[Path]) -> None:
    """Make numba's reading of the cache files under `folders` map module names (once a
    process; a later call adds its folders). numba's two readers are replaced for those
    folders by the same steps with the mapping unpickler; other folders keep numba's."""
    from numba.core import caching

    files = caching.IndexDataCacheFile
    installed = getattr(files._load_index, "whitted_folders", None)
    if installed is not None:
        installed.extend(f for f in folders if f not in installed)
        return
    original_index, original_data = files._load_index, files._load_data
    ours = list(folders)

    def under_ours(cache_file) -> bool:
        path = Path(cache_file._cache_path)
        return any(path.is_relative_to(folder) for folder in ours)

    def _load_index(self):
        if not under_ours(self):
            return original_index(self)
        # numba's own steps (caching.IndexDataCacheFile._load_index, 0.62 and 0.68)
        try:
            with open(self._index_path, "rb") as f:
                version = pickle.load(f)
                data = f.read()
        except FileNotFoundError:
            return {}
        if version != self._version:
            return {}  # another numba's: the rest may not even unpickle
        stamp, overloads = loads(data)
        return overloads if stamp == self._source_stamp else {}

    def _load_data(self, name):
        if not under_ours(self):
            return original_data(self, name)
        with open(self._data_path(name), "rb") as f:
            loaded = loads(f.read())
        _own_descriptor(loaded)
        return loaded

    _load_index.whitted_folders = ours
    files._load_index, files._load_data = _load_index, _load_data
