"""numba's compile options read in one step (core.jit.flag_values) give the very dict numba's
own `values()` gives, for options unset, set to their defaults and set otherwise, so
hashing and comparing `Flags` (numba's cache of typed implementations is keyed by them)
decide as before."""

import itertools

import numba
import pytest
from numba.core import targetconfig
from numba.core.compiler import Flags

import core.jit.decorators  # noqa: F401 (installs it)

pytestmark = pytest.mark.skipif(numba.config.DISABLE_JIT, reason="no compiles without the JIT")


def _flag_sets():
    """Flags with every combination of a few options unset, set to default, set otherwise."""
    choices = {
        "nrt": (None, False, True),
        "forceinline": (None, False, True),
        "error_model": (None, "python", "numpy"),
        "no_cpython_wrapper": (None, True),
    }
    for picked in itertools.product(*choices.values()):
        flags = Flags()
        for name, value in zip(choices, picked, strict=True):
            if value is not None:
                setattr(flags, name, value)
        yield flags


def test_the_options_read_at_once_are_numbas_own_and_compare_alike():
    values = targetconfig.TargetConfig.values
    original = values.whitted_original  # installed: the import above put it there
    flag_sets = list(_flag_sets())
    for flags in flag_sets:
        assert values(flags) == original(flags)
    # Equal and hashed alike exactly when numba's own reading says so
    for a, b in itertools.combinations(flag_sets[:30], 2):
        same = original(a) == original(b)
        assert (a == b) is same
        if same:
            assert hash(a) == hash(b)
    assert any(a != b for a, b in itertools.combinations(flag_sets[:30], 2))
