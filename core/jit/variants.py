"""Copies of a kernel compiled without some render features (`core.kernels.features`).

A kernel's feature code sits behind a module constant (`if WITH_NODES and programmed:`),
which numba prunes before typing when the constant is False. A variant is the kernel's own
Python function given a copy of its module's globals with the left-out features' constants
set False, and with every kernel it calls that reads a feature, directly or further down,
replaced by that kernel's variant in the same way. Kernels that read no feature are shared
by every variant: they compile once.

Each variant is a kernel of its own to numba: its qualified name carries a tag of the
features it leaves out (`render_tile__without_1fb`), so numba's cache keeps it in an index
file of its own beside the full kernel's, under the same source file and its stamp. One
variant is made once a process (a lock and a table), so it is never compiled twice.

Why copies of the functions rather than a feature argument: an argument's value is not known
when numba types the function, so every branch would be typed and compiled; a literal
argument would be passed down each call, and the kernels type their callees' arguments as
plain values (`core.jit.decorators`); and a jitted function captured in a closure misses
the cache in each new process. A global is constant to numba, and this way the kernels
read as plain code.
"""

from __future__ import annotations

import threading
import types


def _features():
    """core.kernels.features, imported when first needed: the decorators import this module
    before the kernels' package exists (a circular import otherwise)."""
    from ..kernels import features

    return features


# The decorator that made each kernel (py_func -> decorator), so a variant is made as its
# kernel was: `core.jit.decorators` fills it
MADE_BY: dict = {}
# What is done to a variant after its decorator, as to its kernel (never_inlined,
# optimised_alone): py_func -> [mark, ...]
MARKS: dict = {}
_LOCK = threading.RLock()
_VARIANTS: dict = {}  # (py_func, left out) -> dispatcher
_READS_FEATURES: dict = {}  # py_func -> bool


def tag(left_out: frozenset[str]) -> str:
    """The left-out features as a hexadecimal bit set, in FEATURES' order."""
    order = _features().FEATURES
    return format(sum(1 << order.index(f) for f in left_out), "x")


def features_of(bits: str) -> frozenset[str]:
    """The features a tag names (`tag`'s inverse); ValueError for one that is not hexadecimal."""
    value = int(bits, 16)
    return frozenset(f for k, f in enumerate(_features().FEATURES) if value >> k & 1)


def _names(code: types.CodeType):
    """The global names a function's code reads, with those of code nested in it."""
    yield from code.co_names
    for constant in code.co_consts:
        if isinstance(constant, types.CodeType):
            yield from _names(constant)


def _callees(py_func):
    """(name, kernel) of the kernels made here that `py_func` calls by a global name."""
    for name in set(_names(py_func.__code__)):
        value = py_func.__globals__.get(name)
        callee = getattr(value, "py_func", None)
        if callee is not None and callee in MADE_BY:
            yield name, value


def reads_features(py_func) -> bool:
    """Whether the kernel, or a kernel it calls however deep, tests a feature's constant."""
    known = _READS_FEATURES.get(py_func)
    if known is not None:
        return known
    _READS_FEATURES[py_func] = False  # a recursive call tree ends here
    constants = {_features().constant_name(f) for f in _features().FEATURES}
    reads = any(
        name in constants and name in py_func.__globals__ for name in _names(py_func.__code__)
    ) or any(reads_features(callee.py_func) for _, callee in _callees(py_func))
    _READS_FEATURES[py_func] = reads
    return reads


def variant(dispatcher, left_out: frozenset[str]):
    """`dispatcher`'s kernel compiled without the features `left_out` (names of FEATURES);
    the kernel itself when it leaves none out or reads none of them, or when numba's JIT is
    off (a plain Python function: its branches run as they are)."""
    py_func = getattr(dispatcher, "py_func", None)
    if not left_out or py_func is None or py_func not in MADE_BY:
        return dispatcher
    known = _features().FEATURES
    unknown = set(left_out) - set(known)
    if unknown:
        raise ValueError(f"no such kernel features: {sorted(unknown)}; known: {known}")
    with _LOCK:
        return _variant(dispatcher, frozenset(left_out))


def _variant(dispatcher, left_out: frozenset[str]):
    py_func = dispatcher.py_func
    if not reads_features(py_func):
        return dispatcher
    key = (py_func, left_out)
    made = _VARIANTS.get(key)
    if made is not None:
        return made
    module_globals = dict(py_func.__globals__)
    for feature in left_out:
        name = _features().constant_name(feature)
        if name in module_globals:
            module_globals[name] = False
    for name, callee in _callees(py_func):
        module_globals[name] = _variant(callee, left_out)
    copy = types.FunctionType(
        py_func.__code__, module_globals, py_func.__name__, py_func.__defaults__,
        py_func.__closure__,
    )  # fmt: skip
    copy.__kwdefaults__ = py_func.__kwdefaults__
    copy.__module__ = py_func.__module__
    copy.__doc__ = py_func.__doc__
    # The cache's index file is named by the qualified name: one a variant
    copy.__qualname__ = f"{py_func.__qualname__}__without_{tag(left_out)}"
    made = MADE_BY[py_func](copy)
    for mark in MARKS.get(py_func, ()):
        made = mark(made)
    _VARIANTS[key] = made
    return made


def made_variants(dispatcher):
    """(left out, variant) of `dispatcher`'s variants made in this process so far."""
    py_func = getattr(dispatcher, "py_func", None)
    with _LOCK:
        return [(without, made) for (f, without), made in _VARIANTS.items() if f is py_func]
