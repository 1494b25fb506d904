"""Build the zip a Blender user installs: a Blender 4.2+ extension (blender_manifest.toml,
with numba, llvmlite, Pillow and lupa bundled as wheels; Blender brings numpy), and its kernels
compiled for the x86-64-v4 and -v3 feature levels, so that a new install renders without
compiling first (core.portable_cache). Blender 3.4 to 4.1 load the same modules as a legacy add-on
(bl_info) from a checkout's link instead.

    python blender_addon/packaging/build_extension.py OUT_DIR

The zip holds blender_addon/'s manifest and modules, the `core` renderer (found next to
them at import) and the wheels the manifest names, for Linux x86-64 and CPython 3.11
(Blender 4.2 to 5.0's Python). Run by `make addon`.
"""

from __future__ import annotations

import os
import re
import shutil
import subprocess
import sys
import tempfile
import zipfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
ADDON = ROOT / "blender_addon"
# The versions the project pins (pyproject.toml), for Blender's Python 3.11 on Linux
WHEELS = ("numba==0.68.1", "llvmlite==0.50.0", "Pillow==13.0.0", "lupa==2.8")
PLATFORM = ("manylinux2014_x86_64", "manylinux_2_17_x86_64", "manylinux_2_28_x86_64")


def download_wheels(folder: Path) -> list[Path]:
    folder.mkdir(parents=True, exist_ok=True)
    platforms = [arg for p in PLATFORM for arg in ("--platform", p)]
    subprocess.run(
        [sys.executable, "-m", "pip", "download", "--quiet", "--no-deps", "--only-binary=:all:",
         "--python-version", "3.11", *platforms, "--dest", str(folder), *WHEELS],
        check=True,
    )  # fmt: skip
    return sorted(folder.glob("*.whl"))


# The name Blender imports the installed `core` as, for an extension installed from disk into
# the user repository it offers first; numba's cache records it (core.jit), so the shipped
# kernels are compiled under it. Installed into another repository, Whitted compiles its own.
INSTALLED_AS = "bl_ext.user_default.whitted.core"


def compile_kernels(cache_base: Path, level: str, stage: Path) -> Path:
    """Run the kernel warm-up in a process of its own, with its cache in cache_base and
    `core` imported under INSTALLED_AS from a copy in stage, for the portable CPU level
    given, whatever this machine's (which must be able to run it); returns the folder of
    this version's kernels. A complete cache there only loads."""
    from core.jit import kernel_cache_dir
    from core.warmup_process import CHILD_PROGRAM

    core = stage.joinpath(*INSTALLED_AS.split("."))
    if not core.is_dir():
        shutil.copytree(ROOT / "core", core, ignore=shutil.ignore_patterns("__pycache__"))
    env = dict(os.environ, WHITTED_CACHE_DIR=str(cache_base))
    env.update(NUMBA_CPU_NAME=level, NUMBA_CPU_FEATURES="")
    env.pop("PYTHONPATH", None)  # nothing but the staged copy may answer to its name
    subprocess.run(
        [sys.executable, "-c", CHILD_PROGRAM, INSTALLED_AS, str(core)],
        cwd=stage, env=env, check=True,
    )  # fmt: skip
    folder = cache_base / kernel_cache_dir(INSTALLED_AS).name
    marker = folder / f"warm-{level}.ok"
    if not marker.is_file():
        raise SystemExit(f"the kernel warm-up left no {marker}")
    return folder


def build(
    out_dir: Path,
    with_wheels: bool = True,
    kernel_cache: Path | None = None,
    levels: tuple[str, ...] | None = None,
) -> Path:
    """The zip in out_dir, with blender_manifest.toml as it stands in blender_addon/; the
    wheels it names must be the ones downloaded. Without wheels (for tests, offline) their
    list is left out and the extension relies on the numba and Pillow Blender can import.
    The kernels are compiled for each of `levels` (every portable level unless given) with
    their cache in kernel_cache (out_dir/kernel_cache unless given: a second build only
    loads them)."""
    sys.path.insert(0, str(ROOT))
    from core.portable_cache import PORTABLE_LEVELS
    from core.version import VERSION

    manifest = (ADDON / "blender_manifest.toml").read_text()
    if f'version = "{VERSION}"' not in manifest:
        raise SystemExit(f"blender_manifest.toml: version must be {VERSION} (core/version.py)")
    listed = re.findall(r'"\./wheels/([^"]+)"', manifest)
    out_dir.mkdir(parents=True, exist_ok=True)
    wheels = []
    if with_wheels:
        wheels = download_wheels(out_dir / "wheels")
        if sorted(w.name for w in wheels) != sorted(listed):
            raise SystemExit(
                f"downloaded wheels {[w.name for w in wheels]} differ from the manifest's "
                f"{listed}: update blender_addon/blender_manifest.toml"
            )
    else:
        manifest = re.sub(r"wheels = \[.*?\]\n", "", manifest, flags=re.S)
    # Every level's kernels go into the one folder of this version (numba keys each by target)
    with tempfile.TemporaryDirectory() as stage:
        (kernels,) = {
            compile_kernels(kernel_cache or out_dir / "kernel_cache", level, Path(stage))
            for level in levels or tuple(PORTABLE_LEVELS)
        }
    target = out_dir / f"whitted-{VERSION}.zip"
    with zipfile.ZipFile(target, "w", zipfile.ZIP_DEFLATED) as archive:
        archive.writestr("blender_manifest.toml", manifest)
        for path in sorted(ADDON.glob("*.py")):
            archive.write(path, path.name)
        for path in sorted((ROOT / "core").rglob("*.py")):
            archive.write(path, str(path.relative_to(ROOT)))
        # numba's index and machine-code files, in the folders core.portable_cache names
        for path in sorted(kernels.rglob("*")):
            if path.suffix in (".nbi", ".nbc", ".ok"):
                archive.write(path, f"kernel_cache/{kernels.name}/{path.relative_to(kernels)}")
        for wheel in wheels:
            archive.write(wheel, f"wheels/{wheel.name}")
    return target


if __name__ == "__main__":
    print(build(Path(sys.argv[1]) if len(sys.argv) > 1 else ROOT / "dist"))
