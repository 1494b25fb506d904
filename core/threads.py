"""How many threads Whitted's work runs on when the settings leave it to the machine."""

import os


def available_threads() -> int:
    """The processors this process may run on."""
    return len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else os.cpu_count()
