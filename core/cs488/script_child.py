"""The child side of `script_process`: run one scene script here, within the limits the
operating system can enforce on this process, and leave the outcome in a pickle file.

    python -m core.cs488.script_child SCRIPT OUTCOME_FILE OPTIONS_JSON
"""

from __future__ import annotations

import contextlib
import gc
import json
import math
import os
import pickle
import sys
from pathlib import Path

from .sandbox import ScriptError, ScriptLimits
from .script_process import PRINT_MARK, packed

# The child's CPU time may pass the limit by this much: the parent normally acts first
CPU_SPARE_S = 5


def _limit_this_process(limits: ScriptLimits) -> None:
    """The operating system's limits on this child, where it has them: CPU time a little past
    the time limit, address space the memory limit past what the process holds now (Python,
    numpy, Lua: or all of Blender, when Blender's binary runs scripts), no core dumps."""
    try:
        import resource
    except ImportError:  # Windows: the parent's clock and the Lua state's cap remain
        return
    cpu = math.ceil(limits.seconds) + CPU_SPARE_S
    for name, soft, hard in (("RLIMIT_CPU", cpu, cpu + CPU_SPARE_S), ("RLIMIT_CORE", 0, 0)):
        with contextlib.suppress(ValueError, OSError, AttributeError, OverflowError):
            resource.setrlimit(getattr(resource, name), (soft, hard))
    # numpy's matrix products go to OpenBLAS, which maps its work buffer at its first product
    # and, refused by the address-space limit, retries the mapping without end (seen: a
    # 16 MiB limit spun in the kernel until the time limit ran out). So it maps it now,
    # within what the process holds before the limit
    import numpy as np

    np.ones((4, 4)) @ np.ones((4, 4))
    try:
        with open("/proc/self/statm") as statm:  # Linux: the address space, in pages
            held = int(statm.read().split()[0]) * os.sysconf("SC_PAGE_SIZE")
    except OSError:
        return  # macOS does not enforce RLIMIT_AS; the Lua state's cap remains
    allowed = held + limits.memory_mib * 2**20
    with contextlib.suppress(ValueError, OSError, OverflowError):
        resource.setrlimit(resource.RLIMIT_AS, (allowed, allowed))


def _child_main(argv: list[str]) -> int:
    """The child: run the script here within the limits; leave the outcome in the file."""
    from . import load_script_here

    script, outcome_file, options = Path(argv[1]), Path(argv[2]), json.loads(argv[3])
    limits = ScriptLimits(**options["limits"])
    _limit_this_process(limits)
    protocol = sys.stdout
    sys.stdout = sys.stderr  # nothing else may write on the protocol's lines

    def print_line(text: str) -> None:
        protocol.write(PRINT_MARK + json.dumps(text) + "\n")
        protocol.flush()

    sys.setrecursionlimit(max(sys.getrecursionlimit(), 10_000))  # pickling a deep CSG tree
    outcome = None
    try:
        calls = load_script_here(script, print_line, options["anywhere"], limits)
        outcome = ("calls", packed(calls))
        del calls
    except ScriptError as error:
        outcome = ("error", str(error))
    except MemoryError:
        outcome = ("error", f"{script.name}: {limits.memory_message()}")
    # Out of the except block the failed run's frames, and the Lua state they hold, are gone:
    # a script that met its memory limit left nothing to pickle with otherwise
    gc.collect()
    try:
        data = pickle.dumps(outcome, protocol=pickle.HIGHEST_PROTOCOL)
    except MemoryError:
        outcome = None
        gc.collect()
        data = pickle.dumps(("error", f"{script.name}: {limits.memory_message()}"))
    partial = outcome_file.with_suffix(".partial")
    partial.write_bytes(data)
    os.replace(partial, outcome_file)  # the parent sees a whole outcome or none
    return 0


if __name__ == "__main__":
    sys.exit(_child_main(sys.argv))
