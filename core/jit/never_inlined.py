"""Kernels that stay a call of their own: LLVM's `noinline` on them.

`shadow_visibility` (the shadow rays of one light at one shading point: a loop around the
whole shadow-ray search) was meant to be a call, but it was inlined at each of its five call
sites, so the render kernel held five copies of the search, some 45 000 of its 78 000
instructions. numba passes a caller's `forceinline` on to the callees it compiles, and its
callers are inlined kernels, so it got LLVM's alwaysinline too.

Optimising a function and making machine code of it take longer than its length grows:
measured on the render kernel's linked module, module optimisation took 26 s and machine
code 20 s; with that one function kept a call, 9-11 s and 5 s. The call is made private to
the render kernel's module, so that LLVM drops the arguments it never reads (numba passes a
tuple of arrays field by field: of its 317 arguments it reads 89). A call per light per
shading point costs nothing measurable beside the shadow rays it casts: the final scene
renders in the same time (0.52-0.60 s against 0.54-0.64 s at 200², runs alternated) and
to the same bits (inlining changes no arithmetic).

numba has no switch for it, so the declaration of every function numba emits passes through
here (`BaseContext.declare_function`, where numba itself adds `alwaysinline`), and a kernel
marked `never_inlined` gets `noinline` on its definition and at every call site's
declaration. A `core` imported under a second name in one process shares the first one's
set of marks through the installed hook. A numba whose internals differ from the ones this
was written against (0.62 and 0.68) gets a warning and inlines as it would.
"""

from __future__ import annotations

import warnings

from .variants import MARKS


def install() -> set[tuple[str, str]]:
    """numba's declare_function and module optimisation wrapped once per process; returns
    the shared set of (module, qualified name) of the kernels to keep out of line."""
    from numba.core import base, codegen

    declare = base.BaseContext.declare_function
    optimise = getattr(codegen.CPUCodeLibrary, "_optimize_final_module", None)
    if optimise is None:
        warnings.warn(
            "Whitted: this numba's code libraries differ from those Whitted knows; its "
            "shadow-ray search is inlined where it is called, which only compiles slower",
            stacklevel=2,
        )
        return set()
    marked = getattr(declare, "whitted_never_inlined", None)
    if marked is not None:  # installed by another copy of core: share its set
        return marked
    marked = set()
    qualname_of = {}  # LLVM name -> qualified name, of the marked kernels declared so far

    def declare_function(self, module, fndesc):
        fn = declare(self, module, fndesc)
        if (fndesc.modname, fndesc.qualname) in marked:
            fn.attributes.add("noinline")
            qualname_of[fn.name] = fndesc.qualname
        return fn

    def optimise_with_private_calls(self):
        # In the library of a kernel that calls a marked one (not the marked kernel's own,
        # nor a callee's deferred library, which others link: core.jit.deferred), the
        # marked function is made private to the module. LLVM then drops the arguments it
        # never reads and passes the rest in registers first: numba passes a tuple of arrays
        # field by field, and of shadow_visibility's 317 arguments it reads 89.
        if not getattr(self, "whitted_deferred", False):
            for fn in self._final_module.functions:
                if qualname_of.get(fn.name, self.name) != self.name and not fn.is_declaration:
                    fn.linkage = "internal"
        optimise(self)

    declare_function.whitted_never_inlined = marked
    base.BaseContext.declare_function = declare_function
    codegen.CPUCodeLibrary._optimize_final_module = optimise_with_private_calls
    return marked


_MARKED = install()


def never_inlined(dispatcher):
    """Mark a kernel (a numba dispatcher) to be called, never inlined, by the kernels that
    call it."""
    function = getattr(dispatcher, "py_func", dispatcher)
    _MARKED.add((function.__module__, function.__qualname__))
    MARKS.setdefault(function, []).append(never_inlined)  # its variants too (core.jit.variants)
    if hasattr(getattr(dispatcher, "_compiler", None), "targetoptions"):
        # Said outright: numba otherwise passes a caller's `forceinline` on to the callees
        # it compiles (an option "inherited if not set"), and this one, first compiled from
        # an inlined kernel, became LLVM's alwaysinline. A dict of its own: a decorator's
        # dispatchers share one, and the others must keep inheriting
        options = {**dispatcher.targetoptions, "forceinline": False}
        dispatcher.targetoptions = dispatcher._compiler.targetoptions = options
    return dispatcher
