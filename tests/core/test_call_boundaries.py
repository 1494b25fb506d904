"""Where the compiled kernels call and where they inline (core.jit.never_inlined,
core.jit.decorators): a kernel marked `never_inlined` stays a call of its own, private to the
kernel Python calls, even when its callers are inlined kernels (numba passes a caller's
`forceinline` on to its callees); marking it leaves every other kernel's options as they
were; and a callee called with an int32 and with an int64 is compiled once."""

from tests.support.kernel_script import run_kernel_script

# Kernels of the script's own, in a new cache folder: an entry point calls an inlined kernel
# that calls a marked search twice and a plain callee; the entry calls the plain callee too,
# with another integer type
KERNELS = r"""
import json, re
import numpy as np
from core.jit.decorators import inlined_kernel, kernel, never_inlined

@never_inlined
@kernel
def search(a, i):
    total = 0.0
    for j in range(i, a.shape[0]):
        total += a[j] * a[j]
    return total

@kernel
def plain_callee(a, i):
    return a[i] * 2.0

@inlined_kernel
def shade(a, i):
    return search(a, i) + search(a, i + 1) + plain_callee(a, i)

@kernel
def entry(a, rows):
    return shade(a, rows[0]) + plain_callee(a, np.int64(0))

a = np.arange(10.0)
value = entry(a, np.array([3], np.int32))
llvm = entry.inspect_llvm(entry.signatures[0])
defined = [line for line in llvm.splitlines()
           if line.startswith("define") and "6search" in line.split("(")[0]]
calls = [line for line in llvm.splitlines() if " call " in line and "6search" in line]
print(json.dumps({
    "value": value,
    "search_defined": defined,
    "search_calls": len(calls),
    "search_options": search.targetoptions,
    "plain_options": plain_callee.targetoptions,
    "plain_copies": len(plain_callee.overloads),
}))
"""


def test_a_never_inlined_kernel_stays_a_private_call_and_callees_compile_once(tmp_path):
    facts = run_kernel_script(tmp_path, "boundary_kernels.py", KERNELS)
    a = [float(x) for x in range(10)]
    expected = sum(x * x for x in a[3:]) + sum(x * x for x in a[4:]) + 2 * a[3] + 2 * a[0]
    assert facts["value"] == expected
    # One definition, kept out of line and private to the entry's module, called (not
    # inlined into its two call sites: each would copy the whole loop)
    assert len(facts["search_defined"]) == 1, facts["search_defined"]
    definition = facts["search_defined"][0]
    assert definition.startswith("define internal"), definition
    assert facts["search_calls"] >= 1
    assert facts["search_options"]["forceinline"] is False
    # The other kernels' options are their decorator's, untouched (they share one dict)
    assert "forceinline" not in facts["plain_options"]
    # Called with an int32 (read from an array) and an int64: one compiled copy
    assert facts["plain_copies"] == 1
