"""numba kernels over `PackedScene` arrays. Importing this configures the kernel cache."""

from ..jit import decorators  # noqa: F401  (sets numba's cache folder before any kernel is decorated)
