"""Run a test's own kernels in a Python of their own, compiled into a new cache folder, and
read back what the script found: the facts it prints as JSON on its last line."""

import json
import os
import subprocess
import sys
from pathlib import Path

import core

ROOT = os.path.dirname(os.path.dirname(core.__file__))


def run_kernel_script(folder: Path, name: str, source: str) -> dict:
    """Write `source` to folder/name (a file: numba caches kernels by their file), run it with
    a cache folder of its own under `folder`, and return its last line's JSON."""
    script = folder / name
    script.write_text(source)
    run = subprocess.run(
        [sys.executable, str(script)],
        env={**os.environ, "WHITTED_CACHE_DIR": str(folder / "cache"), "PYTHONPATH": ROOT},
        cwd=ROOT, capture_output=True, text=True, timeout=600,
    )  # fmt: skip
    assert run.returncode == 0, run.stderr[-3000:]
    return json.loads(run.stdout.splitlines()[-1])
