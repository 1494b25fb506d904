"""How every kernel is compiled: cached, GIL-free, and into a cache folder per version.

numba reads `config.CACHE_DIR` when a function is decorated, so this module must be imported
(it is, by `core.kernels`) before any kernel module. The folder holds the package, numba and
Python versions so an upgrade never loads stale machine code; tests, benchmarks and Blender
subprocesses share it through the WHITTED_CACHE_DIR environment variable.
"""

import os
import sys
from pathlib import Path

import numba

from core.version import VERSION


def kernel_cache_dir() -> Path:
    base = os.environ.get("WHITTED_CACHE_DIR") or Path.home() / ".cache" / "whitted"
    tag = (
        f"whitted-{VERSION}-numba-{numba.__version__}-py{sys.version_info[0]}{sys.version_info[1]}"
    )
    return Path(base) / tag


numba.config.CACHE_DIR = str(kernel_cache_dir())

# error_model="numpy": division by zero gives inf/nan like numpy instead of a Python exception
# check on every division; the kernels guard their own divisions.
kernel = numba.njit(cache=True, nogil=True, error_model="numpy")
