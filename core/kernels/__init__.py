"""numba kernels over `PackedScene` arrays. Importing this configures the kernel cache."""

import core.jit  # noqa: F401  (sets numba's cache folder before any kernel is decorated)
