"""A tiny cached kernel for the kernel-cache tests: numba caches only functions defined in a
file, and this one compiles in a second."""

from core.jit.decorators import kernel


@kernel
def doubled(x):
    return 2.0 * x
