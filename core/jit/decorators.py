"""How every kernel is compiled: cached, GIL-free, and into a cache folder per version
(`core.jit.cache_folder` names it).

numba reads `config.CACHE_DIR` when a function is decorated, so this module must be imported
(it is, by `core.kernels`) before any kernel module.
"""

import numba
from numba.core import errors, types

from .cache_folder import kernel_cache_dir
from .cache_names import read_any_core_names
from .deferred import defer_callee_compiles, optimised_alone  # noqa: F401 (kernels take it here)
from .flag_values import read_options_at_once
from .healing import heal_damaged_loads
from .never_inlined import never_inlined  # noqa: F401 (kernels take it here)
from .relocatable import choose_cpu_target, use_relocatable_cache_folders
from .variants import MADE_BY

numba.config.CACHE_DIR = str(kernel_cache_dir())
# A damaged cache file of any kernel is removed and that kernel compiled again, not raised
heal_damaged_loads(kernel_cache_dir())
# Kernels cached under another name of `core` load under this one (core.jit.cache_names)
read_any_core_names([kernel_cache_dir()])
# The cache can be moved to another folder and another machine (core.jit.relocatable): the
# extension ships it filled
use_relocatable_cache_folders()
CPU_TARGET = choose_cpu_target()
# A kernel called by kernels is optimised and made into machine code once, in the kernel
# Python calls (core.jit.deferred): half the cold compile
DEFERRED_CALLEES = defer_callee_compiles()
# numba's compile options read in one step where typing hashes and compares them
# (core.jit.flag_values): a tenth of a cold compile
FAST_OPTIONS = read_options_at_once()

# The four-wide BVH's box tests are written as four straight-line copies for LLVM's SLP
# vectorizer to merge into vector instructions (core.kernels.bvh_wide): 1.6x the rays per
# second. numba turned SLP off by default in 0.57 after miscompilations in the LLVM of its
# day (numba#8852); the exact BVH-against-brute-force and watertightness tests guard ours.
# Read when numba first compiles, so this must run before any kernel is compiled.
numba.config.SLP_VECTORIZE = 1


def _plain(argument_type):
    """A callee's argument type as its compiled copy takes it: a constant as a plain value,
    a signed integer narrower than 64 bits as int64."""
    plain = types.unliteral(argument_type)
    if isinstance(plain, types.Integer) and plain.signed and plain.bitwidth < 64:
        return types.int64
    return plain


def _holds_array(t) -> bool:
    if isinstance(t, types.Array):
        return True
    return isinstance(t, types.BaseTuple) and any(_holds_array(e) for e in t.types)


def _refuse_returned_arrays(dispatcher) -> None:
    """A kernel compiled without reference counting must not hand an array to a kernel: a
    caller that counts references (an `allocating_kernel`) would release the array it got,
    though it was never counted for it, and free memory that is still in use (a crash, seen
    in a trial). numba itself refuses only a new array or a view; this also refuses an
    argument handed back. Python's calls are safe (numba returns the object passed in)."""
    for signature in dispatcher.nopython_signatures:
        if _holds_array(signature.return_type):
            raise errors.TypingError(
                f"kernel {dispatcher.py_func.__qualname__} returns an array "
                f"({signature.return_type}) to a kernel: kernels without reference counting "
                "write into arrays their callers pass, and return numbers"
            )


def _one_signature_for_constants(dispatcher):
    """Type calls from other kernels with constants as plain values. numba types a constant
    argument (`row(a, 0)`, `f(x, -1)`, a counter that starts at 0) as a Literal of its own and
    compiles the callee once more for it; measured on the render kernel, such copies of
    the shadow-ray kernel alone added 34 s to a cold compile. None of our kernels needs a
    constant to be known at compile time, so one compiled copy serves all callers.

    Likewise an index read from an int32 array (a shape's row, a material's number) and one
    counted in a loop (int64) made two copies of the callee: the shader program's twice
    (2 s of a cold compile), the mesh search's, the shadow log's and a dozen smaller ones.
    A signed integer is passed as int64 (numba's own integer arithmetic is int64 whatever
    the operands' width, so no result changes)."""
    if numba.config.DISABLE_JIT:
        return dispatcher  # the plain Python function: nothing is typed
    get_call_template = dispatcher.get_call_template

    counts_references = dispatcher.targetoptions.get("_nrt", True)

    def unliteral_call_template(args, kws):
        args = tuple(_plain(a) for a in args)
        kws = {name: _plain(a) for name, a in kws.items()}
        template = get_call_template(args, kws)
        if not counts_references:
            _refuse_returned_arrays(dispatcher)
        return template

    dispatcher.get_call_template = unliteral_call_template
    return dispatcher


# error_model="numpy": division by zero gives inf/nan like numpy instead of a Python exception
# check on every division; the kernels guard their own divisions.
# _nrt=False: no reference counting. A kernel works in arrays its caller made (the packed
# scene, the workspace) and allocates none, so numba's counting of array references did
# nothing but cost: an increment and a decrement lowered at every array argument, view and
# tuple field, then LLVM removing most of them again. Without it a cold compile took 65 s ->
# 57 s (interleaved, median of 3), the pictures bit for bit the same. A kernel that
# allocates (np.empty, an array expression, a slice copied onto a slice) now fails to
# compile ("No implementation of function ... zeros", "NRT required but not enabled"): the
# kernels that build the packed scene allocate, and are `allocating_kernel`s.
_compile = numba.njit(cache=True, nogil=True, error_model="numpy", _nrt=False)


def kernel(function):
    MADE_BY[function] = kernel
    return _one_signature_for_constants(_compile(function))


# Inlined into every caller by LLVM (the function gets LLVM's alwaysinline). For the functions
# called once per ray with several groups of the packed scene: a real call passes a tuple of
# arrays field by field on the stack (measured: a call of `transmittance` per shadow ray made
# the batch 2.6x slower). Inlined by LLVM, not by numba (`inline="always"`): numba inlines
# its own IR, and types and rewrites the callee again at every call site, the callee's
# callees with it, which was two thirds of a cold compile (100 of 150 s, measured with
# NUMBA_CHROME_TRACE); LLVM inlines the callee compiled once. The final scene renders 1.8x
# faster so compiled.
# numba passes `forceinline` on to the callees a kernel's compile compiles (an option it
# "inherits if not set"), so a plain `kernel` first compiled from an inlined one is inlined
# too, and nearly every kernel of the render kernel's tree is: the tree is one function of
# 30 000 instructions. A kernel that must stay a call is marked `never_inlined`
# (core.jit.never_inlined).
_compile_inlined = numba.njit(
    cache=True, nogil=True, error_model="numpy", _nrt=False, forceinline=True
)


def inlined_kernel(function):
    MADE_BY[function] = inlined_kernel
    return _one_signature_for_constants(_compile_inlined(function))


# Inlined by numba itself, for the few small functions repeated side by side as vector lanes
# (`core.kernels.triangles`) or whose results feed such copies (`bvh_wide.child_entries`):
# LLVM inlines a callee it has already optimized alone, where the lane number was not a
# constant, and the copies no longer merge into vector instructions (measured: 10% fewer
# mesh shadow rays per second than inlined by numba). Only small bodies: numba types an
# inlined body again at every call site and every call inside it (inlining the box test's
# eight calls too added 20 s to a cold compile).
_compile_ir_inlined = numba.njit(
    cache=True, nogil=True, error_model="numpy", _nrt=False, inline="always"
)


def ir_inlined_kernel(function):
    MADE_BY[function] = ir_inlined_kernel
    return _compile_ir_inlined(function)


# The kernels that build the packed scene from Python, once a scene (the BVH builder, its
# collapse to eight-wide nodes, the fold of constant materials): they allocate the arrays
# they return, so numba counts their references. Their callees are plain kernels, which
# may read and write the arrays these pass them but must not return one (a test checks
# that no kernel without reference counting returns an array).
_compile_allocating = numba.njit(cache=True, nogil=True, error_model="numpy")


def allocating_kernel(function):
    MADE_BY[function] = allocating_kernel
    return _compile_allocating(function)
