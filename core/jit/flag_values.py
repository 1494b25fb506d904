"""numba's compile options read in one step rather than one property at a time: a tenth of a
cold compile.

numba looks up a typed call's implementation in a cache keyed by the compile's options (its
`Flags`), so every call site typed hashes and compares them (the hash covers the options'
names only, so every lookup compares), and `TargetConfig.values()`, which both use, reads
each of some forty options through a property that looks up the set value or the default:
measured on the warm-up, 356 000 calls of `values()` and eight million property reads, 5 s
of a 52 s cold compile (interleaved, median of 3: 51.8 -> 46.9 s).

Here `values()` is the options' defaults, taken once a class, updated with the options
set: the same dict (the property returns the set value, or the option's default object),
so hashing and comparing give what they gave. If numba's `TargetConfig` differs from the
one this was written against (0.62 to 0.68), or the two disagree on a fresh `Flags`, it is
left as it is.
"""

from __future__ import annotations

import warnings


def read_options_at_once() -> bool:
    """Install the faster `values()` (once a process); returns whether it is on."""
    from numba.core import targetconfig
    from numba.core.compiler import Flags

    config = targetconfig.TargetConfig
    if getattr(config.values, "whitted_original", None) is not None:
        return True  # a `core` imported under another name installed it
    original = config.values
    defaults: dict[type, dict] = {}

    def values(self):
        kind = type(self)
        known = defaults.get(kind)
        if known is None:
            known = defaults[kind] = {name: o.default for name, o in kind.options.items()}
        return {**known, **self._values}

    values.whitted_original = original
    try:
        sample = Flags()
        sample.nrt = True  # one option set, the rest defaults
        agrees = values(sample) == original(sample) and values(Flags()) == original(Flags())
    except (AttributeError, TypeError) as error:
        warnings.warn(f"Whitted: numba's options are read the slower way ({error!r})", stacklevel=2)
        return False
    if not agrees:
        warnings.warn("Whitted: numba's options are read the slower way", stacklevel=2)
        return False
    config.values = values
    return True
