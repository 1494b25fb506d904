"""Every cached kernel heals the same way when its cache files are damaged.

numba trusts its cache files: an index or data file cut short (a full disk, a process killed
while writing), zeroed or garbled makes the load of that function raise from deep in numba's
cache reader (`EOFError: Ran out of input`, `UnpicklingError`), whichever function it is: the
render kernel, or one the compile step calls from Python (the BVH builder). Wrapped here,
numba's one place of loading a cached function (`Cache.load_overload`) treats such an error,
for Whitted's cache folder only, as a miss: the function's files go, the first such in a
process is said in one line, and numba compiles the function and writes its files anew.
Each function's cached machine code is whole in its own files (what it inlined was compiled
into it), so the other files stay: only the damaged functions compile again.
"""

from __future__ import annotations

import contextlib
import glob
import os
import sys
from pathlib import Path

healed: list[str] = []  # the functions healed in this process, for callers to report


def heal_damaged_loads(folder: Path) -> None:
    """Make numba's loading of cached functions under `folder` heal damage (once a process)."""
    from numba.core import caching

    if getattr(caching.Cache.load_overload, "whitted_folder", None) is not None:
        caching.Cache.load_overload.whitted_folder = Path(folder)
        return
    original = caching.Cache.load_overload

    def load_overload(self, sig, target_context):
        try:
            return original(self, sig, target_context)
        except Exception as error:
            if not _under(self, load_overload.whitted_folder):
                raise  # another add-on's numba cache: not ours to remove
            _forget(self, error)
            return None  # a miss: numba compiles the function and caches it again

    load_overload.whitted_folder = Path(folder)
    caching.Cache.load_overload = load_overload


def _under(cache, folder: Path) -> bool:
    path = getattr(cache, "_cache_path", None)
    try:
        return path is not None and Path(path).resolve().is_relative_to(folder.resolve())
    except (OSError, RuntimeError):
        return False


def _forget(cache, error: BaseException) -> None:
    """Remove one function's index and data files, mark the folder, and say so."""
    files = cache._cache_file
    removed = [files._index_path]
    pattern = files._data_name_pattern.replace("{number:d}", "*")
    removed += glob.glob(os.path.join(glob.escape(files._cache_path), pattern))
    for path in removed:
        with contextlib.suppress(OSError):
            os.remove(path)
    function = getattr(cache, "_py_func", None)
    name = getattr(function, "__qualname__", None) or Path(files._index_path).stem
    if module := getattr(function, "__module__", None):
        name = f"{module.rpartition('.')[2]}.{name}"
    healed.append(name)
    if len(healed) > 1:
        return  # one line a process: a full disk damages many functions at once
    reason = f"{type(error).__name__}: {error}"[:200]
    print(
        f"Whitted: the kernel cache's copy of {name} was damaged ({reason}); removed it and "
        "compiling it again (any other damaged copy likewise, without a word)",
        file=sys.stderr,
        flush=True,
    )
