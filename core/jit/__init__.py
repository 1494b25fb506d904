"""How Whitted's numba kernels are compiled, cached, shipped and warmed, in one place.

- `decorators`: the three ways a kernel is compiled (`kernel`, `inlined_kernel`,
  `ir_inlined_kernel`) and numba's settings; imported (by `core.kernels`) before any kernel.
- `never_inlined`: the kernels kept a call of their own (LLVM's `noinline`), so that the
  render kernel holds one copy of the shadow-ray search, not five.
- `deferred`: a callee's compile finished once, inside the kernel Python calls.
- `flag_values`: numba's compile options read in one step when typing compares them.
- `cache_folder`: the cache folder of this version, the extension's shipped
  kernels copied into it, old versions' folders pruned.
- `cache_names`: kernels cached under one import name of `core` loaded under another.
- `relocatable`: one cache serving any folder `core` is unpacked in and any x86-64 CPU of a
  feature level, so the extension can ship it.
- `healing`: a damaged cache file removed and its kernel compiled again, as numba loads it.
- `warmup`: compiling every kernel once, ahead of the first render (`python -m` runs it).
- `warmup_process`: the warm-up in a process of its own, watched from Blender's.
- `child_process`: how a child Python imports this very `core` (the warm-up; Lua scripts).

Nothing here imports numba on the package's import: a Lua script's child process uses
`child_process` alone and pays no numba import.
"""
