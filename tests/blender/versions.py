"""Every Blender the add-on is tested in, and the virtual environment each `bpy` module lives in.

Blender 3.4 is Debian's binary (`blender -b`). The others are `bpy`, Blender as a Python
module from PyPI, each pinned with the numpy that Blender version brings: 5.0 in the project's
own `.venv`, the rest in `.venvs/bpy-<version>` with the project's other pins (pyproject.toml);
4.5's with the older numba that Intel Macs get.
Blender 5.1 and later run CPython 3.13, found on this machine by `python_for` or named by
PYTHON313.

`make test` runs the whole suite in the project's `.venv` (bpy 5.0, Blender 3.4's binary),
then, for each other version, every test that imports `bpy` (tests/blender, marked `bpy`), in
that version's environment; in 5.2's (numpy 2, Python 3.13) the kernels' tests too, and in 4.5's
(numba 0.62.1) those of the kernel cache, of the deferred compiles and of the kept calls,
which patch numba.

    python -m tests.blender.versions venv 5.2    build the environment of one version
    python -m tests.blender.versions test 5.2    run its tests
"""

from __future__ import annotations

import glob
import os
import shutil
import subprocess
import sys
from dataclasses import dataclass
from pathlib import Path

from blender_addon.packaging.build_extension import INTEL_MAC_NUMBA

ROOT = Path(__file__).resolve().parents[2]


@dataclass(frozen=True)
class BpyVersion:
    blender: str  # "4.2": what a user calls it
    python: str  # "3.11": the CPython the bpy wheel is built for
    pins: tuple[str, ...]  # bpy itself and the numpy that Blender bundles
    tests: tuple[str, ...] = ("-m", "bpy and not blender34", "tests/blender")  # what runs in it

    @property
    def venv(self) -> Path:
        if self.blender == IN_PROJECT_VENV:
            return ROOT / ".venv"
        return ROOT / ".venvs" / f"bpy-{self.blender}"

    @property
    def interpreter(self) -> Path:
        return self.venv / "bin" / "python"


IN_PROJECT_VENV = "5.0"
# Blender 3.4's binary tests and the zips' wheel checks run in the project's venv only
ONCE = ("-m", "not blender34", "--ignore=tests/blender/test_platform_zips.py")
# The Blender tests, those of the kernel cache, whose stamps numba 0.62 makes otherwise,
# and those of the deferred compiles and the kept calls, which change numba's internals
CACHE_TOO = (
    *ONCE,
    "tests/blender",
    "tests/core/test_portable_cache.py",
    "tests/core/test_warmup_process.py",
    "tests/core/test_deferred_compile.py",
    "tests/core/test_call_boundaries.py",
    "tests/core/test_reference_counting.py",
    "tests/core/test_flag_values.py",
)
# Under Python 3.13 and numba's build for it (Blender 5.1 and later), what differs: the
# kernels (compiled by another numba, the variants pruned from another bytecode), the
# numba internals the compile patches, the add-on and the zip; the rest of the core is
# the same Python over numpy and runs once, in the project's venv
# A variant renders its scene as the full kernel by its source (a feature's constant False
# changes nothing a scene without it reaches): what Python 3.13 changes is the bytecode numba
# prunes, which the plain scene's variant, leaving out the most features, prunes most of.
# The other two scenes' variants (80 s of this lane) are compared under 3.11 only
VARIANTS_ONCE = tuple(
    f"--deselect=tests/core/test_kernel_variants.py::"
    f"test_a_variant_renders_its_scene_as_the_full_kernel[{name}]"
    for name in ("blender", "world")
)
KERNELS_TOO = (
    *CACHE_TOO,
    "tests/core/kernels",
    "tests/core/test_kernel_variants.py",
    *VARIANTS_ONCE,
    "tests/core/test_kernel_cache.py",
    "tests/core/test_imports.py",
    "tests/core/test_driver.py",
    "tests/core/test_render_accuracy.py",
    "tests/core/test_lighting.py",
    "tests/core/test_shader_programs.py",
    "tests/core/test_photon_grid.py",
)
BPY_VERSIONS = (
    BpyVersion("4.2", "3.11", ("bpy==4.2.23", "numpy==1.26.4")),
    # With the numba an Intel Mac gets (the last Blender there)
    BpyVersion("4.5", "3.11", ("bpy==4.5.15", "numpy==1.26.4", *INTEL_MAC_NUMBA), CACHE_TOO),
    BpyVersion("5.0", "3.11", ("bpy==5.0.1", "numpy==1.26.4")),
    # The one with numpy 2 and Python 3.13: the kernels' tests run here too
    BpyVersion("5.2", "3.13", ("bpy==5.2.3", "numpy==2.5.5"), KERNELS_TOO),
)
# Blender's own binary, run with `blender -b`: Debian's package
BLENDER_BINARY_VERSIONS = ((3, 4),)
SUPPORTED = {tuple(map(int, v.blender.split("."))) for v in BPY_VERSIONS}
SUPPORTED |= set(BLENDER_BINARY_VERSIONS)


def package(pin: str) -> str:
    return pin.split("==")[0].lower()


def project_pins(overridden: tuple[str, ...]) -> list[str]:
    """The project's own runtime and test pins, less those a version pins itself."""
    import tomllib  # not in Blender 3.4's Python 3.10, which imports SUPPORTED

    project = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]
    extras = project["optional-dependencies"]
    pins = project["dependencies"] + extras["test"] + extras["bench"]  # tests draw charts too
    return [p for p in pins if package(p) not in {"bpy", *map(package, overridden)}]


def python_for(version: str) -> str | None:
    """A CPython of this minor version that runs: PYTHON<major><minor> if set, else the first
    found on PATH, in pyenv's versions folder or the usual prefixes. pyenv's shims are skipped,
    since a shim for a version that is not pyenv's global one refuses to run."""
    named = os.environ.get("PYTHON" + version.replace(".", ""))
    candidates = [named] if named else []
    candidates += [shutil.which(f"python{version}") or ""]
    home = os.environ.get("PYENV_ROOT", os.path.expanduser("~/.pyenv"))
    candidates += sorted(glob.glob(f"{home}/versions/{version}*/bin/python{version}"), reverse=True)
    candidates += [f"/usr/bin/python{version}", f"/usr/local/bin/python{version}"]
    for candidate in filter(None, candidates):
        try:
            run = subprocess.run(
                [candidate, "-c", "import sys, venv; print('%d.%d' % sys.version_info[:2])"],
                capture_output=True, text=True, timeout=60,
            )  # fmt: skip
        except OSError:
            continue
        if run.returncode == 0 and run.stdout.strip() == version:
            return candidate
    return None


def build_venv(version: BpyVersion) -> None:
    python = python_for(version.python)
    if python is None:
        raise SystemExit(
            f"Blender {version.blender}'s bpy needs CPython {version.python}, and none was found "
            f"(looked for python{version.python} on PATH and in pyenv's versions folder): "
            f"install it (`pyenv install {version.python}`, or your system's "
            f"python{version.python} and python{version.python}-venv packages) or name it with "
            f"PYTHON{version.python.replace('.', '')}=/path/to/python{version.python}"
        )
    subprocess.run([python, "-m", "venv", "--clear", str(version.venv)], check=True)
    pip = [str(version.interpreter), "-m", "pip", "install", "--quiet"]
    subprocess.run([*pip, "--upgrade", "pip"], check=True)
    subprocess.run([*pip, *version.pins, *project_pins(version.pins)], check=True)


def run_tests(version: BpyVersion) -> int:
    print(f"== Blender {version.blender} (bpy in {version.venv.relative_to(ROOT)})", flush=True)
    command = [str(version.interpreter), "-m", "pytest", "-p", "no:cacheprovider", "-q"]
    command += ["--durations=8"]  # where its first compiles show
    return subprocess.run([*command, *version.tests], cwd=ROOT).returncode


def main(action: str, blender: str) -> int:
    (version,) = [v for v in BPY_VERSIONS if v.blender == blender]
    if action == "venv":
        build_venv(version)
        return 0
    return run_tests(version)


if __name__ == "__main__":
    sys.exit(main(*sys.argv[1:3]))
