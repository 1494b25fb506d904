"""The kernel cache's folders: this version's named, the extension's shipped kernels copied
in, old versions' folders pruned. A damaged cache file heals as numba loads it
(core.jit.healing).

The folder's name holds the package, numba and Python versions and a hash of the kernels'
source: numba checks only a cached function's own file for changes, not the files of the
functions it calls, so without the hash an edit to one kernel module could leave stale
machine code inlined in another. Not the name `core` is imported under: one folder serves
them all (core.jit.cache_names), so a checkout's tests, Blender's add-on and the
extension's zip compile each kernel once per Python and numba. Tests, benchmarks and
Blender subprocesses share the folder through WHITTED_CACHE_DIR.

The extension ships its kernels compiled (`make addon`; core.jit.relocatable says how one
cache serves other folders and machines): the first look for a complete cache copies them
into the user's cache folder, so a new install renders without compiling.

Every kernel edit or upgrade starts a new cache folder, so old ones are removed once unused
for a while.
"""

import contextlib
import hashlib
import os
import shutil
import sys
import time
from pathlib import Path

import numba

from ..version import VERSION
from . import healing
from .relocatable import CORE, PACKAGE_ROOT

# The import name of the `core` this package belongs to (`core` in a checkout,
# `bl_ext.user_default.whitted.core` in the extension)
CORE_PACKAGE = __package__.rpartition(".")[0]


def _another_core_imported() -> bool:
    """Whether another Whitted `core` (not an alias of this one, as a checkout's add-on
    makes) was imported in this process first."""
    this = sys.modules.get(__name__)
    return any(
        name.endswith("jit.cache_folder") and module is not this
        and hasattr(module, "kernel_source_hash")
        for name, module in list(sys.modules.items())
    )  # fmt: skip


# The second of two cores in one process keeps a folder of its own: loading the first's
# kernels too would define each function's machine code twice under one name
SECOND_CORE = _another_core_imported()


def kernel_source_hash() -> str:
    digest = hashlib.sha1(CORE_PACKAGE.encode() if SECOND_CORE else b"")
    # how kernels are compiled (decorators.py, never_inlined.py) and found and stamped
    # (relocatable.py) too; and vocabulary.py, whose codes the kernels compile in as constants
    here = Path(__file__).parent
    sources = [here / "decorators.py", here / "never_inlined.py", here / "relocatable.py",
               CORE / "vocabulary.py", *(CORE / "kernels").glob("*.py")]  # fmt: skip
    for path in sorted(sources):
        digest.update(path.name.encode() + path.read_bytes())
    return digest.hexdigest()[:12]


def kernel_cache_dir() -> Path:
    """This version's cache folder."""
    base = os.environ.get("WHITTED_CACHE_DIR") or Path.home() / ".cache" / "whitted"
    python = f"py{sys.version_info[0]}{sys.version_info[1]}"
    tag = f"whitted-{VERSION}-numba-{numba.__version__}-{python}-{kernel_source_hash()}"
    return Path(base) / tag


# Where the extension's zip holds its compiled kernels: beside `core`, one folder a version
SHIPPED_KERNELS = PACKAGE_ROOT / "kernel_cache"
# A cache folder no render has used this long is removed after a warm-up fills a new one
STALE_DAYS = 30


def load_or_rebuild(get_kernels):
    """get_kernels() (which compiles the kernels or loads them from the cache). Returns (its
    result, whether a damaged cached kernel was compiled again meanwhile)."""
    healed_before = len(healing.healed)
    return get_kernels(), len(healing.healed) > healed_before


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
