"""A damaged kernel cache heals itself: noticed, removed, rebuilt, said in one line.

numba trusts its cache files: a file cut short (a full disk, a process killed while writing),
zeroed or garbled makes every later load of that kernel raise from deep in numba's cache
reader (`EOFError`, `UnpicklingError` and the like), so every render would fail until the user
found and deleted the folder. Such an error is told apart from any other by where it was
raised: in numba's cache reader. Then the whole cache folder of this version goes (a kernel's
cached copy may be inlined in another's, so no single file can be trusted alone), and the
kernels compile again.

The extension ships its kernels compiled (`make addon`; core.portable_cache says how one
cache serves other folders and machines): the first look for a complete cache copies them
into the user's cache folder, so a new install renders without compiling.

Every kernel edit or upgrade starts a new cache folder (its name holds the versions and a
hash of the kernel sources), so old ones are removed once unused for a while.
"""

import contextlib
import os
import shutil
import sys
import time
from pathlib import Path

from . import cache_healing
from .cache_healing import REFUSED
from .jit import kernel_cache_dir
from .portable_cache import PACKAGE_ROOT

# Where the extension's zip holds its compiled kernels: beside `core`, one folder a version
SHIPPED_KERNELS = PACKAGE_ROOT / "kernel_cache"
# A cache folder no render has used this long is removed after a warm-up fills a new one
STALE_DAYS = 30

_NUMBA_CACHE = str(Path("numba") / "core" / "caching.py")


def raised_reading_cache(error: BaseException) -> bool:
    """Whether `error` was raised while numba read a cached kernel (in one of its cache
    module's load functions: an error while writing, a full disk say, is not damage, and
    compiling again would only meet it again)."""
    trace = error.__traceback__
    while trace is not None:
        code = trace.tb_frame.f_code
        if code.co_filename.endswith(_NUMBA_CACHE) and code.co_name.lstrip("_").startswith("load"):
            return True
        trace = trace.tb_next
    return False


def load_or_rebuild(get_kernels):
    """get_kernels() (which compiles the kernels or loads them from the cache); if it fails
    reading a damaged cache, remove the cache folder, say so on stderr, and call it again.
    Returns (its result, whether the cache was rebuilt). Damage to one function's files is
    healed as numba loads it (core.cache_healing); this catches what that cannot see."""
    healed_before = len(cache_healing.healed)
    try:
        return get_kernels(), len(cache_healing.healed) > healed_before
    except Exception as error:
        if not raised_reading_cache(error):
            raise
        folder = kernel_cache_dir()
        shutil.rmtree(folder, ignore_errors=True)
        folder.mkdir(parents=True, exist_ok=True)
        (folder / REFUSED).touch()
        print(
            f"Whitted: the kernel cache was damaged ({type(error).__name__}: {error}); "
            f"removed {folder} and compiling the kernels again",
            file=sys.stderr,
            flush=True,
        )
        return get_kernels(), True


def shipped_kernels() -> Path:
    return SHIPPED_KERNELS / kernel_cache_dir().name


def copy_shipped_kernels(marker: str) -> bool:
    """Copy the extension's compiled kernels for this version into the user's cache folder
    if they were compiled for this CPU target (their warm-up left `marker`) and the folder
    has no complete warm-up of its own. Each file lands whole (copied aside, then renamed), so
    a render reading the folder meanwhile sees the old file or the new one; the marker comes
    last. Returns whether it copied."""
    source, target = shipped_kernels(), kernel_cache_dir()
    if not (source / marker).is_file() or (target / marker).is_file():
        return False
    if (target / REFUSED).exists():
        return False
    files = [p for p in source.rglob("*") if p.is_file() and p.name != marker]
    for path in [*files, source / marker]:
        destination = target / path.relative_to(source)
        destination.parent.mkdir(parents=True, exist_ok=True)
        partial = destination.with_name(f".{destination.name}.{os.getpid()}.partial")
        shutil.copyfile(path, partial)
        os.replace(partial, destination)
    print(
        f"Whitted: copied the extension's compiled kernels ({marker}) into {target}",
        file=sys.stderr,
        flush=True,
    )
    return True


def note_use() -> None:
    """Mark this version's cache folder as used now (its time is what pruning reads)."""
    with contextlib.suppress(OSError):  # a cache folder one may only read: nothing to prune
        os.utime(kernel_cache_dir())


def prune_stale(keep_days: float = STALE_DAYS) -> list[Path]:
    """Remove the other versions' cache folders beside this one that were not used for
    keep_days (only Whitted's, named whitted-*: the folder above may be shared). Another
    Blender with another Whitted still in use keeps its own. Returns what was removed."""
    current = kernel_cache_dir()
    if not current.parent.is_dir():
        return []
    cutoff = time.time() - keep_days * 86400
    removed = []
    for folder in current.parent.glob("whitted-*"):
        if folder != current and folder.is_dir() and folder.stat().st_mtime < cutoff:
            shutil.rmtree(folder, ignore_errors=True)
            removed.append(folder)
    return removed
