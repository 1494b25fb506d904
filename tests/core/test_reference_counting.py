"""Kernels compile without numba's reference counting (core.jit.decorators): a kernel that
allocates fails to compile, saying so; an `allocating_kernel` (the packed scene's builders)
allocates and passes its arrays to plain kernels, which write into them; a plain kernel that
hands an array back to a kernel is refused at compile time, naming it (an allocating caller
would free memory it does not own: a crash); and plain kernels' code holds no counting."""

import importlib
import pkgutil

import numba

import core.kernels
from tests.support.kernel_script import run_kernel_script

# The script's own kernels, in a new cache folder (numba caches kernels by their file)
KERNELS = r"""
import json
import numpy as np
from core.jit.decorators import allocating_kernel, kernel

@kernel
def allocates(n):
    return np.zeros(n).sum()

@kernel
def copies_a_slice(a, b):
    a[0:2] = b[1:3]  # numba copies the source first where the two may overlap
    return a[0]

@kernel
def hands_back(a):
    return a

@allocating_kernel
def builds_and_gets_back(n):
    return hands_back(np.ones(n)).sum()

@kernel
def writes(a, x):
    a[0] = x
    a[1:3] = x + 1.0  # a slice filled with a number: no copy, no allocation
    return a.shape[0]

@allocating_kernel
def builds(n):
    b = np.zeros(n)
    writes(b, 2.0)
    return b

def error_of(call):
    try:
        call()
    except Exception as error:
        return f"{type(error).__name__}: {error}"
    return None

facts = {
    "allocates": error_of(lambda: allocates(3)),
    "copies_a_slice": error_of(lambda: copies_a_slice(np.zeros(3), np.ones(3))),
    "hands_back_to_allocating": error_of(lambda: builds_and_gets_back(3)),
    "hands_back_to_python": hands_back(np.arange(3.0)).tolist(),
    "built": builds(4).tolist(),
}
facts["writes_llvm_counts"] = "NRT_" in writes.inspect_llvm(writes.signatures[0])
facts["builds_llvm_counts"] = "NRT_" in builds.inspect_llvm(builds.signatures[0])
print(json.dumps(facts))
"""


def test_kernels_do_not_count_references_and_cannot_allocate(tmp_path):
    facts = run_kernel_script(tmp_path, "counting_kernels.py", KERNELS)
    assert "No implementation of function Function(<built-in function zeros>)" in (
        facts["allocates"] or ""
    ), facts["allocates"]
    assert "NRT required but not enabled" in (facts["copies_a_slice"] or ""), facts
    refused = facts["hands_back_to_allocating"]
    assert refused and "kernel hands_back returns an array" in refused, refused
    assert facts["hands_back_to_python"] == [0.0, 1.0, 2.0]
    assert facts["built"] == [2.0, 3.0, 3.0, 0.0]
    assert facts["writes_llvm_counts"] is False
    assert facts["builds_llvm_counts"] is True


# The kernels that allocate: the packed scene's builders, called from Python once a scene
ALLOCATING = {"build_bvh", "collapse_choices", "collapse_to_wide", "fold_surfaces"}


def test_only_the_scene_builders_count_references():
    counting = set()
    for info in pkgutil.iter_modules(core.kernels.__path__):
        module = importlib.import_module(f"core.kernels.{info.name}")
        for name, value in vars(module).items():
            if not isinstance(value, numba.core.dispatcher.Dispatcher):
                continue
            is_ours = value.py_func.__module__ == module.__name__
            if is_ours and value.targetoptions.get("_nrt", True):
                counting.add(name)
    assert counting == ALLOCATING
