"""A kernel that other kernels call is optimised and turned into machine code once, inside
the kernel Python calls, rather than once more in every kernel above it.

numba compiles every function into a library of its own and finishes each one completely:
it links in the libraries of all the functions it calls, runs LLVM's full optimisation over
the whole, makes machine code of it and a Python wrapper. So a function deep in the call
tree (a triangle test) is optimised and made into machine code again in every kernel above
it (the mesh tracer, the nearest-hit search, the ray tracer, the render kernel), and the
render kernel's tree was optimised some twenty times over. Measured on the warm-up
(`core.jit.warmup`): 165 s cold, of which 54 s were LLVM's optimiser, 45 s machine code
and 20 s Python wrappers that nothing called.

Here a kernel compiled while another kernel is being compiled (a callee, found while typing
its caller) is only lowered to LLVM IR, with its own functions' optimisation: no module
optimisation, no machine code, no wrapper, nothing written to the cache. Its caller links
it as before, and the kernel that Python called optimises and compiles the whole tree once.
The pictures are the same bit for bit (LLVM's optimiser keeps IEEE arithmetic exact: numba
asks for no fast-math and no fused multiply-add), and render as fast (0.99-1.00x, whole
process, interleaved).

Optimising the whole tree only at its top is not always cheaper: the nearest-hit and
shadow-ray searches, optimised only inside the render kernel, made its optimisation take
121 s against 25 s when they arrive optimised. Those two are `optimised_alone`: their
deferred compile still optimises them (no machine code). With them the warm-up took 91 s
(it took 141-165 s); marking five more large callees saved nothing. (It takes 64-77 s now
that the shadow-ray search is no longer inlined five times: core.jit.never_inlined.)

A callee whose compile was deferred has no entry point Python could call: if Python calls
it later, it is compiled again in full (its own callees' deferred libraries serve again).

Only compiles that start in this `core` are deferred (another add-on's numba is left as
numba makes it). A `core` imported under a second name in the same process (the tests'
`core` beside Blender's `whitted.core`) shares the first one's hooks, scope, marks and
compile stack. `WHITTED_FULL_CALLEE_COMPILES=1` turns it off, for comparison and for a
numba whose internals differ from the ones this was written against (0.62 and 0.68); such a
numba gets numba's own way, with a warning.
"""

from __future__ import annotations

import os
import threading
import warnings

from .cache_folder import CORE_PACKAGE
from .variants import MARKS

SWITCH = "WHITTED_FULL_CALLEE_COMPILES"


class DeferredEntry:
    """What a deferred callee has in place of an entry point: a key under which its callers
    find its library and native function, callable by no one."""

    __slots__ = ("name",)

    def __init__(self, name: str):
        self.name = name

    def __repr__(self) -> str:
        return f"<deferred compile of {self.name}>"


class _Compiles(threading.local):
    """The dispatchers being compiled on this thread, outermost first."""

    def __init__(self):
        self.stack = []


_COMPILES = _Compiles()
# The `core` packages (one per name a `core` is imported under) whose compiles defer callees
_PACKAGES: set[str] = set()


# The kernels whose deferred compiles are optimised on their own all the same (no machine
# code): `optimised_alone`
_OPTIMISED_ALONE: set = set()


def optimised_alone(dispatcher):
    """Mark a callee to be optimised on its own when its compile is deferred (still no machine
    code). For the large searches the render kernel inlines: optimised inside it, the
    render kernel's optimisation took 121 s, against 25 s when these arrive optimised."""
    function = getattr(dispatcher, "py_func", dispatcher)
    _OPTIMISED_ALONE.add(function)
    MARKS.setdefault(function, []).append(optimised_alone)  # its variants too (core.jit.variants)
    return dispatcher


def _in_scope() -> bool:
    if not _COMPILES.stack:
        return False
    module = getattr(getattr(_COMPILES.stack[0], "py_func", None), "__module__", "") or ""
    return any(module == p or module.startswith(p + ".") for p in _PACKAGES)


def _defers(flags) -> bool:
    """Whether the function being lowered now is a callee to defer: compiled inside another
    compile of ours (depth 2 and more), or a subroutine numba lowers for a caller of ours
    (which numba already marks as not compiled on its own)."""
    if not _in_scope():
        return False
    return len(_COMPILES.stack) >= 2 or bool(flags.no_compile)


def is_deferred(dispatcher, signature) -> bool:
    """Whether `dispatcher`'s overload for `signature` (a tuple of numba types) is deferred."""
    overload = dispatcher.overloads.get(tuple(signature))
    # By name: a `core` imported under a second name shares the first one's DeferredEntry
    return overload is not None and type(overload.entry_point).__name__ == "DeferredEntry"


def compile_as_callee(dispatcher, *args) -> None:
    """Compile `dispatcher` for `args` (values) as its callers will call it: deferred, so
    with no machine code of its own (that would serve only a call from Python). The warm-up
    compiles the render kernel's large callees in steps of their own this way, so that its
    progress says where it is. Without the deferral, a call compiles it."""
    if not _PACKAGES:
        dispatcher(*args)
        return
    from numba import typeof

    _COMPILES.stack.append(dispatcher)  # as if a kernel of ours were compiling it
    try:
        dispatcher.compile(tuple(typeof(a) for a in args))
    finally:
        _COMPILES.stack.pop()


def defer_callee_compiles() -> bool:
    """Install the deferral into numba (once a process, whichever `core` asks first); returns
    whether it is on."""
    if os.environ.get(SWITCH, "") not in ("", "0"):
        return False
    import numba

    if numba.config.DISABLE_JIT:
        return False
    from numba.core import codegen

    global _OPTIMISED_ALONE, _COMPILES, _PACKAGES
    installed = getattr(codegen.CPUCodeLibrary.finalize, "whitted_deferred", None)
    if installed is not None:
        # Another `core` installed it: share its scope, marks and compile stack, so that
        # this one's `compile_as_callee` pushes where the installed hooks look
        _PACKAGES, _OPTIMISED_ALONE, _COMPILES = installed
        _PACKAGES.add(CORE_PACKAGE)
        return True
    try:
        _install(_PACKAGES)
    except (AttributeError, ImportError) as error:  # a numba this was not written against
        warnings.warn(f"Whitted: kernels compile the slower way ({error!r})", stacklevel=2)
        return False
    _PACKAGES.add(CORE_PACKAGE)
    return True


def _install(packages: set[str]) -> None:
    from numba.core import caching, codegen, dispatcher, event, sigutils, typed_passes
    from numba.core.compiler_lock import require_global_compiler_lock

    # Check everything first, so that a numba that differs is left untouched
    lower_run = typed_passes.BaseNativeLowering.run_pass
    finalize = codegen.CPUCodeLibrary.finalize
    add_overload = dispatcher._DispatcherBase.add_overload
    compile_ = dispatcher.Dispatcher.compile
    save_overload = caching.Cache.save_overload
    _ = codegen.CPUCodeLibrary._get_module_for_linking, codegen.CPUCodeLibrary._raise_if_finalized

    class CompileStack(event.Listener):
        def on_start(self, ev):
            _COMPILES.stack.append(ev.data["dispatcher"])

        def on_end(self, ev):
            _COMPILES.stack.pop()

    event.register("numba:compile", CompileStack())

    def deferring_lower(self, state):
        if not _defers(state.flags):
            return lower_run(self, state)
        subroutine = bool(state.flags.no_compile)
        state.flags.no_compile = True
        state.flags.no_cpython_wrapper = True
        state.flags.no_cfunc_wrapper = True
        if state.library is None:
            state.library = state.targetctx.codegen().create_library(state.func_id.func_qualname)
            state.library.enable_object_caching()
        state.library.whitted_deferred = True
        compiling = getattr(_COMPILES.stack[-1], "py_func", None)
        state.library.whitted_optimise = not subroutine and compiling in _OPTIMISED_ALONE
        changed = lower_run(self, state)
        if not subroutine:
            # What numba does with a compiled function's entry point: callers look its
            # library up under this key
            lowered = state["cr"]
            key = DeferredEntry(state.func_id.func_qualname)
            state.targetctx.insert_user_function(key, lowered.fndesc, [state.library])
            state["cr"] = lowered._replace(cfunc=key)
        return changed

    def deferred_finalize(self):
        if not getattr(self, "whitted_deferred", False):
            return finalize(self)
        # numba's finalize up to the linking: the caller optimises what it links
        require_global_compiler_lock()
        self._raise_if_finalized()
        seen = set()
        for library in self._linking_libraries:
            if library not in seen:
                seen.add(library)
                if hasattr(self, "_reload_init"):  # numba 0.63 and later
                    self._reload_init.update(library._reload_init)
                self._final_module.link_in(library._get_module_for_linking(), preserve=True)
        if getattr(self, "whitted_optimise", False):
            self._optimize_final_module()
        self._finalized = True

    deferred_finalize.whitted_deferred = (packages, _OPTIMISED_ALONE, _COMPILES)

    def add_callable_overload(self, cres):
        if isinstance(cres.entry_point, DeferredEntry):
            # Known to typing and to callers' lowering; Python's calls find no entry and ask
            # for a compile (below)
            self.overloads[tuple(cres.signature.args)] = cres
            return
        add_overload(self, cres)

    def compile_for_python(self, sig):
        if not _COMPILES.stack:  # asked by Python: a deferred overload will not do
            args, _ = sigutils.normalize_signature(sig)
            if is_deferred(self, args):
                del self.overloads[tuple(args)]
        return compile_(self, sig)

    def save_callable_overload(self, sig, data):
        if isinstance(getattr(data, "entry_point", None), DeferredEntry):
            return  # no machine code to save; the kernels above it hold its code
        save_overload(self, sig, data)

    typed_passes.BaseNativeLowering.run_pass = deferring_lower
    codegen.CPUCodeLibrary.finalize = deferred_finalize
    dispatcher._DispatcherBase.add_overload = add_callable_overload
    dispatcher.Dispatcher.compile = compile_for_python
    caching.Cache.save_overload = save_callable_overload
