"""Borrowed arrays: the packed scene with numba's reference counting switched off.

numba reference-counts every array it hands to a function that it does not inline, with an
atomic increment and decrement, even when the callee only reads it. A packed scene holds
some fifty arrays, and a pixel makes a handful of such calls: those atomics measured a third
of the render time on one thread, and worse on two (both threads count the same arrays).

The entry points called from Python (one per tile, or per batch of rays) therefore rebuild
the scene from "borrowed" copies of its arrays: the same data, shape and strides, but no
owner (a null meminfo), which numba's reference counting skips. This is safe because the
Python caller holds the real arrays for the whole call, and no borrowed array is stored or
returned.

A kernel that receives borrowed arrays cannot see that they have no owner, and keeps the
reference counting it would do for owned ones; re-borrowing its arguments at its top (a
copy of a few fields, no memory touched) lets LLVM drop it all. The kernels called per
shading point do so: a shadow ray cast from such a kernel cost 850 ns, 190 ns re-borrowed.

`borrowed` walks its argument's numba type: an array is copied without its owner, a tuple
or named tuple (`PackedScene`, `Workspace` and their groups) is rebuilt from its borrowed
fields in their own order, anything else passes through. No list of fields is kept here,
so a field added to `core.kernels.layout` or `core.kernels.workspace` is borrowed with the
rest, and fields cannot be swapped (tests/core/kernels/test_borrow.py checks both).

With the JIT disabled (NUMBA_DISABLE_JIT=1, for Python tracebacks from kernels) there is no
reference counting to avoid, and `borrowed` returns its argument.
"""

import numba
from numba import types
from numba.core import cgutils
from numba.extending import intrinsic

# The fields of numba's array structure that describe the data; `meminfo` (the owner) and
# `parent` (the Python object) are left null
_ARRAY_VIEW_FIELDS = ("data", "shape", "strides", "itemsize", "nitems")


def _borrow(context, builder, value_type, value):
    if isinstance(value_type, types.Array):
        source = context.make_array(value_type)(context, builder, value)
        copy = context.make_array(value_type)(context, builder)
        for field in _ARRAY_VIEW_FIELDS:
            setattr(copy, field, getattr(source, field))
        copy.parent = cgutils.get_null_value(copy.parent.type)
        copy.meminfo = cgutils.get_null_value(copy.meminfo.type)
        return copy._getvalue()
    if isinstance(value_type, types.BaseTuple):
        fields = [
            _borrow(context, builder, field_type, builder.extract_value(value, i))
            for i, field_type in enumerate(value_type.types)
        ]
        return context.make_tuple(builder, value_type, fields)
    return value


@intrinsic
def _borrowed(typingctx, value):
    """The same value with every array in it unowned: reference counting passes them by.
    An array, or a (named) tuple of arrays and tuples, to any depth."""

    def codegen(context, builder, signature, args):
        return _borrow(context, builder, signature.args[0], args[0])

    return value(value), codegen


def _unchanged(value):
    """Without the JIT, arrays are Python objects: nothing to borrow."""
    return value


borrowed = _unchanged if numba.config.DISABLE_JIT else _borrowed
