"""The kernel cache's folders: the extension's shipped kernels copied in, old versions'
folders pruned. A damaged cache file heals as numba loads it (core.cache_healing).

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
from .jit import kernel_cache_dir
from .portable_cache import PACKAGE_ROOT

# Where the extension's zip holds its compiled kernels: beside `core`, one folder a version
SHIPPED_KERNELS = PACKAGE_ROOT / "kernel_cache"
# A cache folder no render has used this long is removed after a warm-up fills a new one
STALE_DAYS = 30


def load_or_rebuild(get_kernels):
    """get_kernels() (which compiles the kernels or loads them from the cache). Returns (its
    result, whether a damaged cached kernel was compiled again meanwhile)."""
    healed_before = len(cache_healing.healed)
    return get_kernels(), len(cache_healing.healed) > healed_before


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
