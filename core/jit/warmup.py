"""Compile every kernel a render needs before a render asks, in steps that report progress.

A cold compile takes tens of seconds. Blender must not wait on it with a frozen window, so
the add-on runs this module as a program in a process of its own (`core.jit.warmup_process`),
which fills the shared kernel cache and prints one progress line a step; the render then
only loads the cache. The command line runs the same steps in-process.

Each step compiles one group of kernels for a scene that holds one of every kind of thing
(shapes, a mesh, CSG, a texture, both kinds of light). Since every scene packs into the same
array types (`core.compile.kernel_ready`), kernels compiled for it serve every scene; the
largest kernels the render kernel calls are compiled first, each on its own, so that the
steps show where a compile is, and the render kernel finds them done. They are compiled as
the render kernel's callees (`core.jit.deferred`): optimised and made into machine code once,
within it, since no render calls them from Python.

A warm-up compiles the full render kernel, which renders every scene, or a variant without
some features (core.kernels.features, core.jit.variants): `--without TAG` (a bit set of
FEATURES, core.jit.variants.tag) compiles that variant, and the photon pass's kernels only
if it holds caustics. `blender -b` and the command line warm the variant a scene needs (about
half the compile); Blender's window warms the full kernel at start-up, for every scene after.

A marker file in the cache folder says that all steps of a warm-up finished there (one per
variant), so the add-on starts no process when the cache holds the kernels a render needs.
"""

from __future__ import annotations

import contextlib
import math
import os
import re
import subprocess
import sys
import time
from collections.abc import Callable
from pathlib import Path

import numpy as np

from .cache_folder import (
    CORE_PACKAGE,
    STALE_DAYS,
    copy_shipped_kernels,
    kernel_cache_dir,
    prune_stale,
)
from .decorators import CPU_TARGET
from .deferred import compile_as_callee
from .variants import features_of, tag, variant

PROGRESS_PREFIX = "Whitted: compiling kernels: "
READY_PREFIX = "Whitted: kernels ready"
# One for each CPU target: a cache folder can hold the kernels of several (core.jit.relocatable)
MARKER = f"warm-{CPU_TARGET}.ok"
# One for each Python: a cache folder holds each Python's kernels apart (numba keys them by
# its version), and a process compiling one Python's need not wait for another's (the
# suite's lanes compile Blender 4.5's and 5.2's kernels while a window test waits on 3.4's)
LOCK = f"warm-py{sys.version_info[0]}{sys.version_info[1]}-{CPU_TARGET}.lock"
# The packing's and photon pass's kernels compiled beside the rest (in a process of their
# own), unless this is set
SERIAL_SWITCH = "WHITTED_SERIAL_WARMUP"
BESIDE = "--beside"
CACHE_LINE = "Whitted: kernel cache "


def warmup_scene(glowing_texture: bool = True):
    """A small scene with one of everything a packed scene can hold. Its node material is
    constant: the compile folds it into the table with a kernel of its own (`fold_surfaces`),
    which every variant's warm-up compiles, since a scene the variant without node programs
    renders may still hold constant node materials, as most of Blender's do (a default
    Principled BSDF, a Glass BSDF): without it, such a scene's first render compiled the
    fold itself, 8 s after the warm-up said the kernels were ready.

    `glowing_texture`: a mesh whose emission is a texture, which lights the scene: its
    emission is baked by a kernel of its own (core.kernels.glow_bake), which only a variant
    with node programs and emitters needs."""
    from .. import (
        AreaLight,
        Box,
        Csg,
        Cylinder,
        Link,
        Material,
        Mesh,
        PanelLight,
        PointLight,
        Scene,
        ShaderNode,
        Sphere,
        SphereLight,
        Texture,
        Torus,
        TriangleMesh,
    )

    def moved(x):
        m = np.eye(4)
        m[0, 3] = x
        return m

    # A tetrahedron: enough triangles for a mesh BVH with a leaf
    vertices = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], float)
    triangles = np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]])
    checker = np.zeros((2, 2, 3))
    checker[0, 0] = checker[1, 1] = 1.0
    glass = Material(transparency=0.5, reflectivity=0.3)
    # A node material (folded by the compile, whose fold kernel it compiles)
    node_material = Material(surface=ShaderNode("diffuse", {"Color": (0.8, 0.2, 0.2)}))
    glowing = []
    if glowing_texture:
        pattern = Link(ShaderNode("checker", {"Scale": 2.0}), "Color")
        emission = Material(surface=ShaderNode("emission", {"Color": pattern}))
        glowing.append(Mesh("Glowing texture", emission, world_from_object=moved(10),
                            mesh=TriangleMesh(vertices, triangles)))  # fmt: skip
    return Scene(
        shapes=[
            Sphere("Sphere", glass, world_from_object=moved(-2)),
            Torus("Torus", world_from_object=moved(2)),
            Mesh("Mesh", mesh=TriangleMesh(vertices, triangles), world_from_object=moved(4)),
            Csg("Csg", operation="difference", left=Box("Box"), right=Cylinder("Cylinder")),
            Sphere("Textured", Material(texture=Texture(pixels=checker)), moved(6)),
            Sphere("Node material", node_material, moved(8)),
            *glowing,
        ],
        lights=[
            PointLight((0.0, -4.0, 4.0), (1.0, 1.0, 1.0)),
            AreaLight((0.0, 0.0, 4.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (5.0, 5.0, 5.0)),
            SphereLight(position=(1.0, -3.0, 4.0), power=(100.0, 100.0, 100.0), radius=0.5),
            PanelLight(centre=(0.0, 0.0, 5.0), power=(100.0, 100.0, 100.0)),
        ],
    )


def warmup_steps(
    without: frozenset[str] = frozenset(), beside: bool = False
) -> list[tuple[str, Callable[[], None]]]:
    """(what it compiles, how) for each step, in order, for the render kernel without the
    features `without` (none: the full kernel).

    `beside`: the scene packing's kernels (and the photon pass's) compile in a process of
    their own from the start (`Beside`), on the other core, while this one compiles the
    searches and the render kernel for the types of an empty scene, which packs without a
    kernel; the last step waits for that process. They share no compile work: the render
    kernel's searches and shading are typed and optimised in each process anyway."""
    from .. import RenderSettings, Scene
    from ..compile import compile_scene
    from ..driver import prepare_kernel
    from ..kernels.light_pyramid import TRAVERSE_ALL
    from ..kernels.render_tile import render_tile
    from ..kernels.trace import closest_hit, transmittance
    from ..kernels.workspace import new_workspace

    packed = []
    stacks = new_workspace(0).stacks
    o, d = (0.0, -5.0, 0.5), (0.0, 1.0, 0.0)

    def pack():
        packed.append(_packed_warmup_scene(without))

    def geometry():
        return packed[0].geometry

    # the searches and the render kernel, for the packed scene's types, in either order
    kernels = [
        ("nearest hits",
         lambda: compile_as_callee(closest_hit, geometry(), o, d, math.inf, stacks)),
        ("shadow rays",
         lambda: compile_as_callee(transmittance, geometry(), o, d, 9.0, stacks, TRAVERSE_ALL)),
        ("render kernel", lambda: prepare_kernel(packed[0], variant(render_tile, without))),
    ]  # fmt: skip
    if beside:
        started = Beside(without)
        packed.append(compile_scene(Scene(), RenderSettings(8, 8)).packed)
        last = "scene packing" if "caustics" in without else "scene packing and caustic photons"
        return [*kernels, (last, started.finish)]
    photons = (
        []
        if "caustics" in without
        else [("caustic photons", lambda: warm_photon_kernels(packed[0]))]
    )
    return [("scene packing", pack), *kernels, *photons]


def warm_photon_kernels(packed) -> None:
    """Compile the photon pass's kernels (core.compile.caustics): the warm-up scene's glass
    ball sends photons, and a few points get their neighbours' distances."""
    from .. import RenderSettings
    from ..compile.caustics import add_caustics, neighbour_distances

    settings = RenderSettings(8, 8, glass_shadows="blocked", caustics=("reflective", "refractive"),
                              caustic_photons=64)  # fmt: skip
    add_caustics(packed, settings)
    neighbour_distances(np.random.default_rng(0).random((64, 3)))


def progress_line(step: int, steps: int, label: str) -> str:
    return f"{PROGRESS_PREFIX}{step} of {steps} ({label})"


# Each step's share of a cold warm-up and the whole's length, as measured on the development
# machine, so that a progress bar moves evenly rather than by fifths: 44-48 s since the
# kernels count no references and numba's options are read at once (2026-12-06: packing
# 26 %, nearest hits 12 %, shadow rays 7 %, the render kernel 55 %; 64-77 s before, 91-96 s
# before the shadow-ray search was a call of its own, 141-175 s before callees' compiles
# were deferred); the photon pass's kernels added 16 s of 93 on a slower machine (2026-12-06,
# issue 44), the shares re-measured there
STEP_SHARES = {"scene packing": 0.22, "nearest hits": 0.12, "shadow rays": 0.05,
               "render kernel": 0.44, "caustic photons": 0.17}  # fmt: skip
# With the packing beside (the usual way on two cores or more: warmup_steps), the steps in
# their order and shares (2026-12-07, the full kernel: nearest hits 6-7 s, shadow rays 3-4 s,
# the render kernel 35-40 s, and what is left of the packing and photons beside 5-10 s)
BESIDE_SHARES = {"nearest hits": 0.12, "shadow rays": 0.06, "render kernel": 0.68,
                 "scene packing": 0.14, "scene packing and caustic photons": 0.14}  # fmt: skip
TYPICAL_WARMUP_S = 56.0
_PROGRESS = re.compile(r"(\d+) of (\d+) \((.*)\)$")


def progress_fraction(line: str, step_seconds: float) -> float | None:
    """How far a warm-up is, 0 to 1, given its last progress line and the seconds since that
    line: the steps before it, plus this step's share in proportion to its typical length
    (never past 95 % of it: a slower machine waits at the step's end, not beyond). None for a
    line that is not a step's."""
    found = _PROGRESS.search(line)
    if found is None:
        return None
    label, step, steps = found.group(3), int(found.group(1)), int(found.group(2))
    # the steps in their order: the packing first, or beside (and waited for last)
    serial = list(STEP_SHARES)
    shares = STEP_SHARES if step <= len(serial) and serial[step - 1] == label else BESIDE_SHARES
    # beside: the three steps, then the wait for the packing (with photons or not: one share)
    order = serial if shares is STEP_SHARES else list(shares)[:4]
    # a variant's warm-up may run fewer steps (no photons): their shares make the whole
    whole = sum(shares.get(lbl, 0.0) for lbl in order[:steps]) or 1.0
    done = sum(shares.get(lbl, 0.0) for lbl in order[: step - 1])
    share = shares.get(label, 0.0)
    within = min(0.95, step_seconds / (share * TYPICAL_WARMUP_S)) if share else 0.0
    return min(1.0, (done + share * within) / whole)


@contextlib.contextmanager
def one_warmup_at_a_time(report: Callable[[str], None]):
    """Hold the cache folder's warm-up lock, waiting (and saying so) while another process
    holds it: two Blenders or farm renders starting at once on one machine would otherwise
    both compile, each at half speed on shared cores. The lock goes with its process, killed
    or not. Without fcntl (Windows) each compiles on its own."""
    try:
        import fcntl
    except ImportError:
        yield
        return
    try:
        kernel_cache_dir().mkdir(parents=True, exist_ok=True)
        lock = open(kernel_cache_dir() / LOCK, "w")  # noqa: SIM115 (the with below closes it)
    except OSError:  # a cache folder one may not write: no lock to share either
        yield
        return
    with lock:
        try:
            fcntl.flock(lock, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except BlockingIOError:
            report(f"{PROGRESS_PREFIX}waiting for another process that compiles them")
            fcntl.flock(lock, fcntl.LOCK_EX)
        yield


def warm_kernels(
    report: Callable[[str], None] = print, without: frozenset[str] = frozenset()
) -> float:
    """Run every step in this process, report(line) before each; returns the seconds taken.
    Writes the marker when all are done. If another process is compiling into the same
    cache, waits for it, and compiles nothing if the cache is complete then."""
    with one_warmup_at_a_time(report):
        if kernels_ready(without):
            report(f"{READY_PREFIX}: the cache is complete (compiled before, or elsewhere)")
            return 0.0
        return _warm_kernels(report, without)


def _warm_kernels(report: Callable[[str], None], without: frozenset[str]) -> float:
    start = time.perf_counter()
    steps = warmup_steps(without, beside=_may_compile_beside())
    took = []
    for number, (label, compile_step) in enumerate(steps, 1):
        report(progress_line(number, len(steps), label))
        step_start = time.perf_counter()
        compile_step()
        took.append(f"{label} {time.perf_counter() - step_start:.1f} s")
    seconds = time.perf_counter() - start
    marker = marker_path(without)
    marker.parent.mkdir(parents=True, exist_ok=True)
    marker.write_text(f"{seconds:.1f} s: " + ", ".join(took) + "\n")
    report(f"{READY_PREFIX} in {seconds:.1f} s (" + ", ".join(took) + ")")
    for folder in prune_stale():
        report(f"Whitted: removed the kernel cache {folder.name}, unused for {STALE_DAYS} days")
    return seconds


def _may_compile_beside() -> bool:
    return (os.cpu_count() or 1) > 1 and os.environ.get(SERIAL_SWITCH, "") in ("", "0")


class Beside:
    """The scene packing's kernels, and the photon pass's unless `without` caustics, compiled
    in a child process started now (`--beside`, by the launcher this process was started
    with); `finish` waits for it, and compiles them here if it failed."""

    def __init__(self, without: frozenset[str]):
        from . import child_process

        self.without = without
        variant = ["--without", tag(without)] if without else []
        self.process = subprocess.Popen(
            child_process.command("jit.warmup", BESIDE, *variant),
            env=child_process.environment(), stdin=subprocess.DEVNULL, stdout=subprocess.PIPE,
            stderr=subprocess.STDOUT, text=True,
        )  # fmt: skip

    def finish(self) -> None:
        output, _ = self.process.communicate()
        if self.process.returncode != 0:
            print(f"Whitted: the packing kernels' compile beside failed, compiling them here: "
                  f"{output[-500:]}", flush=True)  # fmt: skip
            compile_beside(self.without)


def compile_beside(without: frozenset[str]) -> None:
    """What `Beside` compiles: the warm-up scene packed, and its photons traced."""
    packed = _packed_warmup_scene(without)
    if "caustics" not in without:
        warm_photon_kernels(packed)


def _packed_warmup_scene(without: frozenset[str] = frozenset()):
    """The warm-up scene packed, with a glowing texture where the variant draws its light."""
    from .. import RenderSettings
    from ..compile import compile_scene

    glowing_texture = not ({"nodes", "emitters"} & without)
    return compile_scene(warmup_scene(glowing_texture), RenderSettings(8, 8)).packed


def own_core() -> str:
    """This package's import name and folder: a warm-up fills the cache of another process
    only if it compiled the same package under the same name (core.jit.cache_folder)."""
    return f"{CORE_PACKAGE} at {Path(__file__).resolve().parent.parent}"


def marker_path(without: frozenset[str] = frozenset()) -> Path:
    """The marker of the full kernel's warm-up, or of the variant's without `without`."""
    if not without:
        return kernel_cache_dir() / MARKER
    return kernel_cache_dir() / f"warm-{CPU_TARGET}-without-{tag(without)}.ok"


def kernels_ready(without: frozenset[str] = frozenset()) -> bool:
    """Whether a warm-up for this CPU target finished in this version's cache folder, or the
    extension shipped one that is now copied there: of the full kernel, or of a variant
    holding every feature but `without` (one leaving out fewer serves too)."""
    copy_shipped_kernels(MARKER)
    if marker_path().is_file():
        return True
    for marker in kernel_cache_dir().glob(f"warm-{CPU_TARGET}-without-*.ok"):
        bits = marker.name.rsplit("-", 1)[1].removesuffix(".ok")
        with contextlib.suppress(ValueError):
            if features_of(bits) <= without:
                return True
    return False


def main(arguments: list[str] | None = None) -> int:
    """`--without TAG`: the variant without those features (core.jit.variants.tag); `--beside`
    first: the packing's (and photons') kernels alone, for a warm-up (`Beside`)."""
    arguments = sys.argv[1:] if arguments is None else arguments
    beside = arguments[:1] == [BESIDE]  # a warm-up's packing and photon kernels, beside it
    arguments = arguments[1:] if beside else arguments
    without = frozenset()
    if arguments[:1] == ["--without"]:
        without = features_of(arguments[1])
    if beside:
        compile_beside(without)
        return 0
    # The first line names the package compiled, for the parent to check it is its own
    print(f"Whitted: core {own_core()}", flush=True)
    print(f"{CACHE_LINE}{kernel_cache_dir()}", flush=True)
    warm_kernels(lambda line: print(line, flush=True), without)
    return 0


if __name__ == "__main__":
    sys.exit(main())
