"""A cold compile a test makes anyway, kept as the shared kernel cache's first content."""

import os
import shutil
from pathlib import Path


def seed_shared_cache(filled: Path, shared: Path) -> None:
    """Copy the kernel cache `filled` into the shared cache `shared`, each file that the
    shared one has not got, so that the tests after it load what it compiled rather than
    compile it again (in a new checkout: about a minute each). The shared folder may
    exist already, with no kernels or a few (importing `core` makes it), whose files are
    kept. Each file is written under a temporary name and then renamed, the warm-up's
    marker last: a reader sees a whole file or none, and the marker only with the kernels."""
    files = sorted(p for p in filled.rglob("*") if p.is_file())
    files.sort(key=lambda p: p.name.startswith("warm-"))  # markers last
    for source in files:
        target = shared / source.relative_to(filled)
        if target.exists():
            continue
        target.parent.mkdir(parents=True, exist_ok=True)
        staging = target.with_name(f".{target.name}.{os.getpid()}.seeding")
        shutil.copy2(source, staging)
        os.replace(staging, target)
