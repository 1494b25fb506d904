"""Kernel caches that move: one cache folder serves any place `core` is unpacked and any
x86-64 CPU of one feature level, so the extension can ship its kernels compiled.

Two things tie numba's cache to one machine. It names the folder of a module's cached
kernels by a hash of the module's absolute path, so a cache built where the extension is
built is not found where Blender unpacks it; the locator here names it by the module's path
inside the package (`core/kernels`) instead. And numba compiles for the host's exact CPU
(znver5 here) and keys every cached kernel by the CPU's name and features, so a cache built
on one model of CPU never loads on another. Here a CPU compiles instead for the highest of
two x86-64 feature levels it has: x86-64-v4 (AVX-512: Intel Xeons since Skylake, AMD since
Zen 4) or x86-64-v3 (AVX2 and FMA: Intel since Haswell, AMD since Zen); older or other
CPUs compile for themselves. Measured on this znver5 (bench_bvh, Embree/ours per core, two
interleaved rounds each): the host's own 1.25-1.34 primary and 1.11-1.16 shadow, x86-64-v4
1.20-1.22 and 1.10-1.13, x86-64-v3 1.27-1.42 and 1.20-1.25; so v4, not one v3 for all. Set
NUMBA_CPU_NAME to choose yourself.

Sources are stamped by their bytes, not their times. Only numba's own cache files are read;
whether a cached kernel fits is still numba's check (the same source bytes, numba version
and CPU target), so a moved cache that does not fit is compiled over, never run.
"""

import functools
import hashlib
import os
import platform
from pathlib import Path

import llvmlite.binding as llvm
import numba
from numba.core.caching import CacheImpl, UserProvidedCacheLocator

# The `core` folder this package is in, and the one that holds it: cache folders are named
# by paths below that (`core/kernels`), whatever the package is imported as
CORE = Path(__file__).resolve().parent.parent
PACKAGE_ROOT = CORE.parent

# What each level requires, in LLVM's names for the host's features (lower levels included)
_V3 = (
    *("cmov", "cx8", "fxsr", "mmx", "sse", "sse2"),
    *("cx16", "sahf", "popcnt", "sse3", "sse4.1", "sse4.2", "ssse3"),
    *("avx", "avx2", "bmi", "bmi2", "f16c", "fma", "lzcnt", "movbe", "xsave"),
)
_V4 = (*_V3, "avx512f", "avx512bw", "avx512cd", "avx512dq", "avx512vl")
# Highest first: a CPU compiles for the first it has, and the extension ships kernels for each
PORTABLE_LEVELS = {"x86-64-v4": frozenset(_V4), "x86-64-v3": frozenset(_V3)}


class RelocatableCacheLocator(UserProvidedCacheLocator):
    """numba's locator for a cache folder of one's own (config.CACHE_DIR), with each module's
    kernels in the folder of its path inside the package rather than of its absolute path."""

    def __init__(self, py_func, py_file):
        super().__init__(py_func, py_file)
        inside = Path(py_file).resolve().parent.relative_to(PACKAGE_ROOT)
        self._cache_path = os.path.join(numba.config.CACHE_DIR, *inside.parts)

    @classmethod
    def from_function(cls, py_func, py_file):
        if not Path(py_file).resolve().is_relative_to(CORE):
            return None  # not ours: numba's own locators decide
        return super().from_function(py_func, py_file)

    def get_source_stamp(self):
        """The source file by its bytes, not its time: unpacking or copying gives the files
        new times. numba 0.63+ stamps so itself; 0.62, the last with wheels for Intel Macs,
        by time and size."""
        stat = os.stat(self._py_file)
        return _content_stamp(self._py_file, stat.st_mtime_ns, stat.st_size)


@functools.lru_cache(maxsize=256)
def _content_stamp(path: str, mtime_ns: int, size: int) -> str:
    """Read once per file and version of it (every kernel of a module asks)."""
    return hashlib.sha256(Path(path).read_bytes()).hexdigest()


def host_portable_level() -> str | None:
    """The highest portable level this CPU has, or None (not x86-64, or older than v3)."""
    if platform.machine().lower() not in ("x86_64", "amd64"):
        return None
    features = llvm.get_host_cpu_features()
    for level, required in PORTABLE_LEVELS.items():
        if all(features.get(name, False) for name in required):
            return level
    return None


def choose_cpu_target() -> str:
    """Set numba's CPU target (before anything compiles) and return its name."""
    if os.environ.get("NUMBA_CPU_NAME"):
        return os.environ["NUMBA_CPU_NAME"]  # the user's choice, read by numba itself
    level = host_portable_level()
    if level is None:
        return llvm.get_host_cpu_name()
    numba.config.CPU_NAME = level
    numba.config.CPU_FEATURES = ""  # exactly the level's features, none of the host's
    return level


def use_relocatable_cache_folders() -> None:
    """Ours first; numba's own after it, in numba's order, for kernels outside `core` (the
    list replaces numba's, and names numba's classes as its cache module does)."""
    names = [f"{__name__}.{RelocatableCacheLocator.__name__}"]
    names += [locator.__name__ for locator in CacheImpl._locator_classes]
    numba.config.CACHE_LOCATOR_CLASSES = ",".join(names)
