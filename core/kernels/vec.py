"""3-vectors as tuples of floats: they live in registers, so kernels never allocate for them."""

import math

import numba

from ..jit.decorators import kernel


@kernel
def add(a, b):
    return (a[0] + b[0], a[1] + b[1], a[2] + b[2])


@kernel
def sub(a, b):
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


@kernel
def scale(a, s):
    return (a[0] * s, a[1] * s, a[2] * s)


@kernel
def mul(a, b):
    """Component-wise product (colour times colour)."""
    return (a[0] * b[0], a[1] * b[1], a[2] * b[2])


@kernel
def dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


@kernel
def normalize(a):
    length = math.sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2])
    if length == 0.0:
        return a
    return (a[0] / length, a[1] / length, a[2] / length)


@kernel
def max_abs(a):
    return max(abs(a[0]), abs(a[1]), abs(a[2]))


@kernel
def as_tuple(array):
    """A (3,) array as a tuple."""
    return (array[0], array[1], array[2])


@kernel
def row(array, i):
    """Row i of an (n, 3) array as a tuple."""
    return (array[i, 0], array[i, 1], array[i, 2])


@kernel
def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


@kernel
def affine(m, p):
    """The affine rows of m (its first 3 rows, 4 columns: a (3, 4) or (4, 4) matrix)
    applied to point p."""
    return (
        m[0, 0] * p[0] + m[0, 1] * p[1] + m[0, 2] * p[2] + m[0, 3],
        m[1, 0] * p[0] + m[1, 1] * p[1] + m[1, 2] * p[2] + m[1, 3],
        m[2, 0] * p[0] + m[2, 1] * p[1] + m[2, 2] * p[2] + m[2, 3],
    )


@kernel
def affine_point(matrices, i, p):
    """matrices[i] (3, 4 affine rows) applied to point p, without making a view of it."""
    return (
        matrices[i, 0, 0] * p[0] + matrices[i, 0, 1] * p[1] + matrices[i, 0, 2] * p[2]
        + matrices[i, 0, 3],
        matrices[i, 1, 0] * p[0] + matrices[i, 1, 1] * p[1] + matrices[i, 1, 2] * p[2]
        + matrices[i, 1, 3],
        matrices[i, 2, 0] * p[0] + matrices[i, 2, 1] * p[1] + matrices[i, 2, 2] * p[2]
        + matrices[i, 2, 3],
    )  # fmt: skip


@kernel
def affine_vector(matrices, i, v):
    """The linear part of matrices[i] applied to direction v."""
    return (
        matrices[i, 0, 0] * v[0] + matrices[i, 0, 1] * v[1] + matrices[i, 0, 2] * v[2],
        matrices[i, 1, 0] * v[0] + matrices[i, 1, 1] * v[1] + matrices[i, 1, 2] * v[2],
        matrices[i, 2, 0] * v[0] + matrices[i, 2, 1] * v[1] + matrices[i, 2, 2] * v[2],
    )


@kernel
def affine_transpose_vector(matrices, i, v):
    """The transpose of the linear part of matrices[i] applied to v: carries an
    object-space normal to world space when matrices[i] is object_from_world (normals go
    through the inverse transpose)."""
    return (
        matrices[i, 0, 0] * v[0] + matrices[i, 1, 0] * v[1] + matrices[i, 2, 0] * v[2],
        matrices[i, 0, 1] * v[0] + matrices[i, 1, 1] * v[1] + matrices[i, 2, 1] * v[2],
        matrices[i, 0, 2] * v[0] + matrices[i, 1, 2] * v[1] + matrices[i, 2, 2] * v[2],
    )


@kernel
def _inverse(d):
    # + 0.0 turns -0 into +0 (round to nearest), and so its inverse into +inf
    return (1.0 / (d[0] + 0.0), 1.0 / (d[1] + 0.0), 1.0 / (d[2] + 0.0))


def _inverse_in_python(d):
    """Python's float division raises at zero where compiled code (numpy's error model) gives
    the infinity every slab test relies on."""
    return tuple(1.0 / c if c != 0.0 else math.inf for c in d)


# 1 / d per component, +inf where a component is zero, -0 included: a zero's inverse must not
# take its sign, because a line lying in a box's face plane then gives (plane - o) * inverse =
# NaN on one side and -inf on the other, and the slab tests, which skip the NaN, took the -inf
# as the exit: they culled the box (found by the whole-line slab tests, for d = -0)
inverse = _inverse_in_python if numba.config.DISABLE_JIT else _inverse
