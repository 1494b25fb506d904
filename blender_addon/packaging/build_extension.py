"""Build the zips Blender users install: one Blender 4.2+ extension per platform, as Blender's
own `extension build --split-platforms` makes them, each with the numba, llvmlite, Pillow and
lupa wheels of that platform for every Python its Blenders run (Blender installs the ones that
match; it brings numpy itself), and the Linux one with its kernels compiled for the x86-64-v4
and -v3 feature levels, so that a new install renders without compiling first
(core.jit.relocatable). Blender 3.4 to 4.1 load the same modules as a legacy add-on (bl_info)
from a checkout's link instead.

    python blender_addon/packaging/build_extension.py OUT_DIR [PYTHON ...]

Each zip holds blender_addon/'s modules, the `core` renderer as its subpackage, the wheels
and a blender_manifest.toml naming exactly those wheels and that platform. The PYTHONs (this
one if none) each compile the shipped kernels for their own CPython version. Run by `make
addon`, with the project's Python 3.11 and the Python 3.13 of Blender 5.1+.
"""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
import tempfile
import zipfile
from dataclasses import dataclass
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
ADDON = ROOT / "blender_addon"
# The versions the project pins (pyproject.toml)
WHEELS = ("numba==0.68.1", "llvmlite==0.50.0", "Pillow==13.0.0", "lupa==2.8")
# The last numba with wheels for Intel Macs, and its llvmlite; tested in Blender 4.5's
# environment (tests/blender/versions.py)
INTEL_MAC_NUMBA = ("numba==0.62.1", "llvmlite==0.45.1")


@dataclass(frozen=True)
class Platform:
    name: str  # Blender's name for it, as in a manifest's `platforms`
    pip_platform: str  # the newest platform tag pip is to accept (it takes older ones too)
    pythons: tuple[str, ...]  # the CPython versions of the Blenders that run there
    wheels: tuple[str, ...] = WHEELS
    blender_version_max: str | None = None  # the first Blender that no longer runs there


PLATFORMS = (
    Platform("linux-x64", "manylinux_2_28_x86_64", ("3.11", "3.13")),
    Platform("windows-x64", "win_amd64", ("3.11", "3.13")),
    Platform("macos-arm64", "macosx_14_0_arm64", ("3.11", "3.13")),
    # Blender 4.5 is the last for Intel Macs (Python 3.11)
    Platform(
        "macos-x64",
        "macosx_13_0_x86_64",
        ("3.11",),
        (*INTEL_MAC_NUMBA, "Pillow==13.0.0", "lupa==2.8"),
        blender_version_max="5.0.0",
    ),
)
# The one whose kernels this machine can compile (numba's machine code is per OS and CPU)
KERNELS_FOR = "linux-x64"

# The name Blender imports the installed `core` as, for an extension installed from disk into
# the user repository it offers first: the warm-up that checks the shipped kernels imports
# `core` under it, as Blender will (kernels cached under any name load under any other:
# core.jit.cache_names).
INSTALLED_AS = "bl_ext.user_default.whitted.core"


def download_wheels(platform: Platform, folder: Path) -> list[Path]:
    """The platform's wheels for each of its Pythons, in folder (kept: pip downloads only
    what is not there yet)."""
    folder.mkdir(parents=True, exist_ok=True)
    for python in platform.pythons:
        subprocess.run(
            [sys.executable, "-m", "pip", "download", "--quiet", "--no-deps",
             "--only-binary=:all:", "--python-version", python,
             "--platform", platform.pip_platform, "--dest", str(folder), *platform.wheels],
            check=True,
        )  # fmt: skip
    # By name and version: the folder may hold the wheels of earlier pins too
    wanted = tuple(pin.replace("==", "-").lower() + "-" for pin in platform.wheels)
    return sorted(w for w in folder.glob("*.whl") if w.name.lower().startswith(wanted))


def compile_kernels(python: str, cache_base: Path, level: str, stage: Path) -> Path:
    """Run the kernel warm-up in `python`, in a process of its own, with its cache in
    cache_base and `core` imported under INSTALLED_AS from a copy in stage, for the portable
    CPU level given, whatever this machine's (which must be able to run it); returns the
    folder of its kernels. A complete cache there only loads."""
    from core.jit.child_process import PROGRAM, program_arguments
    from core.jit.warmup import CACHE_LINE

    core = stage.joinpath(*INSTALLED_AS.split("."))
    if not core.is_dir():
        shutil.copytree(ROOT / "core", core, ignore=shutil.ignore_patterns("__pycache__"))
    env = dict(os.environ, WHITTED_CACHE_DIR=str(cache_base.absolute()))  # the child runs in stage
    env.update(NUMBA_CPU_NAME=level, NUMBA_CPU_FEATURES="")
    env.pop("PYTHONPATH", None)  # nothing but the staged copy may answer to its name
    lines = subprocess.run(
        [python, "-c", PROGRAM, *program_arguments("jit.warmup", INSTALLED_AS, core)],
        cwd=stage, env=env, check=True, capture_output=True, text=True,
    ).stdout.splitlines()  # fmt: skip
    print(f"{python} {level}: {lines[-1]}", flush=True)
    (folder,) = [line[len(CACHE_LINE) :] for line in lines if line.startswith(CACHE_LINE)]
    marker = Path(folder) / f"warm-{level}.ok"
    if not marker.is_file():
        raise SystemExit(f"the kernel warm-up left no {marker}")
    return Path(folder)


def shipped_kernels(
    cache_base: Path, pythons: tuple[str, ...], levels: tuple[str, ...]
) -> list[Path]:
    """The kernel folders of every Python for every level (numba keys each kernel by its
    target, so one folder per Python holds all levels)."""
    with tempfile.TemporaryDirectory() as stage:
        return sorted(
            {
                compile_kernels(python, cache_base, level, Path(stage))
                for python in pythons
                for level in levels
            }
        )


def platform_manifest(template: str, platform: Platform, wheels: list[Path]) -> str:
    manifest = template.replace('platforms = ["linux-x64"]', f'platforms = ["{platform.name}"]')
    if platform.blender_version_max:
        newest = f'blender_version_max = "{platform.blender_version_max}"\n'
        manifest = manifest.replace("license = ", newest + "license = ")
    if wheels:
        listed = "".join(f'  "./wheels/{w.name}",\n' for w in wheels)
        manifest = manifest.replace("[permissions]", f"wheels = [\n{listed}]\n\n[permissions]")
    return manifest


def write_zip(target: Path, manifest: str, wheels: list[Path], kernels: list[Path]) -> Path:
    with zipfile.ZipFile(target, "w", zipfile.ZIP_DEFLATED) as archive:
        archive.writestr("blender_manifest.toml", manifest)
        for path in sorted(ADDON.rglob("*.py")):
            inside = path.relative_to(ADDON)
            if inside.parts[0] != "packaging":  # the build's own tools stay out
                archive.write(path, str(inside))
        for path in sorted((ROOT / "core").rglob("*.py")):
            archive.write(path, str(path.relative_to(ROOT)))
        # numba's index and machine-code files, in the folders core.jit.relocatable names
        for folder in kernels:
            for path in sorted(folder.rglob("*")):
                if path.suffix in (".nbi", ".nbc", ".ok"):
                    archive.write(path, f"kernel_cache/{folder.name}/{path.relative_to(folder)}")
        for wheel in wheels:
            archive.write(wheel, f"wheels/{wheel.name}")
    return target


def build(
    out_dir: Path,
    with_wheels: bool = True,
    kernel_cache: Path | None = None,
    levels: tuple[str, ...] | None = None,
    pythons: tuple[str, ...] = (sys.executable,),
    platforms: tuple[str, ...] | None = None,
    wheel_cache: Path | None = None,
) -> dict[str, Path]:
    """The zip of each platform (all unless named) in out_dir, by platform name. Without
    wheels (for tests, offline) the manifest lists none and the extension relies on the numba
    and Pillow Blender can import. The Linux zip's kernels are compiled by each of `pythons`
    for each of `levels` (every portable level unless given; none if empty) with their cache
    in kernel_cache: unless given, the checkout's own (WHITTED_CACHE_DIR, as `make` sets it),
    whose kernels load under the extension's name too (core.jit.cache_names), so the zip
    ships the kernels the tests and renders compiled, and compiles only what they did not;
    else out_dir/kernel_cache (a second build only loads them).
    Wheels are downloaded into wheel_cache (out_dir/wheels unless given)."""
    sys.path.insert(0, str(ROOT))
    from core.jit.relocatable import PORTABLE_LEVELS
    from core.version import VERSION

    template = (ADDON / "blender_manifest.toml").read_text()
    if f'version = "{VERSION}"' not in template:
        raise SystemExit(f"blender_manifest.toml: version must be {VERSION} (core/version.py)")
    out_dir.mkdir(parents=True, exist_ok=True)
    levels = tuple(PORTABLE_LEVELS) if levels is None else levels
    zips = {}
    for platform in PLATFORMS:
        if platforms is not None and platform.name not in platforms:
            continue
        wheels = []
        if with_wheels:
            wheels = download_wheels(platform, (wheel_cache or out_dir / "wheels") / platform.name)
        kernels = []
        if platform.name == KERNELS_FOR and levels:
            shared = os.environ.get("WHITTED_CACHE_DIR")
            cache = kernel_cache or (Path(shared) if shared else out_dir / "kernel_cache")
            kernels = shipped_kernels(cache, pythons, levels)
        manifest = platform_manifest(template, platform, wheels)
        target = out_dir / f"whitted-{VERSION}-{platform.name}.zip"
        zips[platform.name] = write_zip(target, manifest, wheels, kernels)
    return zips


if __name__ == "__main__":
    out = Path(sys.argv[1]) if len(sys.argv) > 1 else ROOT / "dist"
    # Absolute, as the warm-ups run elsewhere; not resolved, or a venv's python leaves its venv
    pythons = tuple(os.path.abspath(p) for p in sys.argv[2:]) or (sys.executable,)
    for name, path in build(out, pythons=pythons).items():
        print(f"{name}: {path} ({path.stat().st_size / 1e6:.0f} MB)")
