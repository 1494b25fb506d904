"""The command line: render a CS488 Lua scene script to the PNG it names.

    python -m core render scene.lua [-o picture.png] [--threads N] [--allow-outside-files]
                                    [--script-seconds S] [--script-memory MIB]
                                    [--passes depth,normal,...|all]
                                    [--caustics both] [--photons N] [--glass-shadows RULE]

The script runs first, to the end, in a child process within its time and memory limits;
only then is anything rendered, so a script with an error anywhere writes nothing. Each
image is written to a temporary file beside its target and renamed into place when complete:
an error or Ctrl-C never leaves a partial PNG. `--passes` also writes each pass asked for to
PICTURE.PASS.exr beside the PNG (core.pass_files), renamed into place with it. Exit status:
0 done, 1 bad script or scene, 2 bad command line, 130 interrupted.
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

from .cs488 import ScriptError, ScriptLimits, load_script
from .cs488.render_options import CAUSTICS, NO_OPTIONS, RenderOptions
from .cs488.sandbox import (
    DEFAULT_LIMITS,
    MAX_SCRIPT_MEMORY_MIB,
    MAX_SCRIPT_SECONDS,
    MIN_SCRIPT_MEMORY_MIB,
    MIN_SCRIPT_SECONDS,
)
from .errors import SceneError
from .farm import command as farm_command
from .model.settings import AUTO_PHOTONS, DEFAULT_CAUSTIC_PHOTONS, MAX_CAUSTIC_PHOTONS
from .output_file import OutputError, check_writable, write_whole
from .passes import PASS_NAMES, check_passes, crypto_names
from .vocabulary import GLASS_SHADOWS

BAR_WIDTH = 30
MAX_THREADS = 1024  # past any machine's cores


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="python -m core", description=__doc__.split("\n")[0])
    commands = parser.add_subparsers(dest="command", required=True)
    render_command = commands.add_parser("render", help="render a CS488 Lua scene script")
    render_command.add_argument("script", type=Path, help="the .lua scene script")
    render_command.add_argument(
        "-o", "--output", type=Path, help="write the image here instead of gr.render's file"
    )
    render_command.add_argument(
        "--threads",
        type=_bounded(int, 0, MAX_THREADS, "threads"),
        default=0,
        help="worker threads (default: one per core)",
    )
    render_command.add_argument(
        "--allow-outside-files", action="store_true",
        help="let the script read and write files outside its own folder",
    )  # fmt: skip
    render_command.add_argument(
        "--passes", type=_pass_list, default=(), metavar="LIST",
        help="also write these passes, each to PICTURE.PASS.exr beside the PNG: a comma-"
        f"separated list of {', '.join(PASS_NAMES)}, or 'all'",
    )  # fmt: skip
    render_command.add_argument(
        "--region", type=_region, default=None, metavar="X,Y,W,H",
        help="render only this part of the image, in pixels from the top left, and write it "
        "cropped (a farm's border task); its pixels are those of the whole render",
    )  # fmt: skip
    render_command.add_argument(
        "--adaptive-shadows", action="store_true",
        help="adaptive soft shadows: probe each area light at nine points first and cast its "
        "shadow rays only where the probes disagree (faster; may miss an occluder narrower "
        "than the light); without it, the report's picture exactly",
    )  # fmt: skip
    render_command.add_argument(
        "--caustics", choices=tuple(CAUSTICS), default=None,
        help="trace light off mirrors (reflective), through glass (refractive) or both onto "
        "diffuse surfaces as photons, over the script's gr.render options (default: the "
        "script's; the report's scripts: none)",
    )  # fmt: skip
    render_command.add_argument(
        "--photons", type=_auto_or(_bounded(int, 0, MAX_CAUSTIC_PHOTONS, "photons")),
        default=None, metavar="N|auto",
        help=f"caustic photons traced (default {DEFAULT_CAUSTIC_PHOTONS}: as many as the "
        "caustics in the frame need)",
    )  # fmt: skip
    render_command.add_argument(
        "--glass-shadows", choices=tuple(GLASS_SHADOWS), default=None,
        help="shadow rays through glass: attenuated by it (the report's rule) or blocked "
        "(the light behind glass then comes as refractive caustics); default: blocked with "
        "refractive caustics, else attenuated",
    )  # fmt: skip
    default = DEFAULT_LIMITS
    render_command.add_argument(
        "--script-seconds", default=default.seconds, metavar="S",
        type=_bounded(float, MIN_SCRIPT_SECONDS, MAX_SCRIPT_SECONDS, "seconds"),
        help=f"stop the scene script after S seconds (default {default.seconds:g})",
    )  # fmt: skip
    render_command.add_argument(
        "--script-memory", default=default.memory_mib, metavar="MIB",
        type=_bounded(int, MIN_SCRIPT_MEMORY_MIB, MAX_SCRIPT_MEMORY_MIB, "MiB"),
        help=f"memory the scene script may take, in MiB (default {default.memory_mib})",
    )  # fmt: skip
    farm_command.add_arguments(
        commands.add_parser("farm", help="render a .blend or .lua scene on a Dask cluster")
    )
    args = parser.parse_args(argv)
    if args.command == "farm":
        return farm_command.run(args)
    limits = ScriptLimits(seconds=args.script_seconds, memory_mib=args.script_memory)
    caustics = CAUSTICS[args.caustics] if args.caustics is not None else None
    options = RenderOptions(caustics, args.photons, args.glass_shadows)
    try:
        return _render_script(
            args.script, args.output, args.threads, args.allow_outside_files, limits, args.passes,
            args.region, args.adaptive_shadows, options,
        )  # fmt: skip
    except (ScriptError, SceneError, OutputError) as error:
        print(f"error: {error}", file=sys.stderr)
        return 1
    except KeyboardInterrupt:
        print("\ninterrupted: no image written", file=sys.stderr)
        return 130


def _bounded(kind, low, high, unit: str):
    """An argparse type: a number of `kind` from low to high, refused in the option's terms
    (a number past any sensible one overflowed the operating system's limits)."""

    def parse(text: str):
        try:
            value = kind(text.strip())
        except (ValueError, OverflowError):
            value = None
        if value is None or not low <= value <= high:
            whole = " whole" if kind is int else ""
            shown = "," if kind is int else ",g"  # 10,000,000, not 1e+07
            raise argparse.ArgumentTypeError(
                f"got {text[:40]!r}; give a{whole} number of {unit} from {low:{shown}} to "
                f"{high:{shown}}"
            )
        return value

    parse.__name__ = kind.__name__  # argparse names the type in its messages
    return parse


def _auto_or(parse):
    """An argparse type: "auto", or what `parse` takes."""

    def parse_or_auto(text: str):
        if text.strip().lower() == AUTO_PHOTONS:
            return AUTO_PHOTONS
        try:
            return parse(text)
        except argparse.ArgumentTypeError as error:
            raise argparse.ArgumentTypeError(f"{error}, or {AUTO_PHOTONS}") from None

    parse_or_auto.__name__ = parse.__name__
    return parse_or_auto


def _pass_list(text: str) -> tuple[str, ...]:
    names = PASS_NAMES if text.strip() == "all" else tuple(n.strip() for n in text.split(","))
    try:
        return check_passes("--passes", names)
    except SceneError as error:
        raise argparse.ArgumentTypeError(error.problem) from None


def _region(text: str) -> tuple[int, int, int, int]:
    try:
        x, y, w, h = (int(v) for v in text.split(","))
    except ValueError:
        raise argparse.ArgumentTypeError(f"got {text!r}; give X,Y,WIDTH,HEIGHT in pixels") from None
    return x, y, w, h  # checked against the image by the render settings, before rendering


def _render_script(script: Path, output: Path | None, threads: int, anywhere: bool,
                   limits: ScriptLimits, passes: tuple[str, ...] = (),
                   region: tuple[int, int, int, int] | None = None,
                   adaptive_shadows: bool = False,
                   options: RenderOptions = NO_OPTIONS) -> int:  # fmt: skip
    calls = load_script(script, print_line=print, anywhere=anywhere, limits=limits,
                        notice=lambda text: print(text, file=sys.stderr, flush=True))  # fmt: skip
    if not calls:
        raise ScriptError(f"{script.name}: the script never calls gr.render: nothing to render")
    if output is not None and len(calls) > 1:
        raise ScriptError(
            f"{script.name}: the script calls gr.render {len(calls)} times; -o names one file"
        )
    if output is not None and output.suffix.lower() != ".png":
        raise ScriptError(f"-o {output}: Whitted writes PNG images; name a file ending in .png")
    for call in calls:  # before any rendering: a path that cannot take the picture
        check_writable(*_target(script, output, call))
        call.settings.threads = threads
        call.settings.passes = passes
        call.settings.region = region
        call.settings.adaptive_shadows = adaptive_shadows
        # the command line's caustics and glass rule over the script's (render_options)
        for name, value in options.over(call.options).settings().items():
            setattr(call.settings, name, value)
        try:  # here, not after a first render's kernel compile
            call.settings.validate()
        except SceneError as error:
            if error.field != "region":
                raise
            raise ScriptError(
                f"--region: {error.problem} ({script.name}'s gr.render size)"
            ) from None
    # Here, not at the top: the farm command, which renders nothing itself, starts without
    # numba's import (a quarter of a second)
    from .compile import compile_scene
    from .driver import kernel_compile_note, render_compiled

    for call in calls:
        for warning in call.warnings:
            print(f"warning: {warning}", file=sys.stderr)
        target, label = _target(script, output, call)
        compiled = compile_scene(call.scene, call.settings, _progress_bar("caustic photons"))
        note = kernel_compile_note(compiled.packed)
        if note:  # the first render of such a scene on a machine: say what it waits for
            print(f"Whitted: {note}", file=sys.stderr, flush=True)
        result = render_compiled(compiled, call.settings, on_tile=_tile_bar())
        print(result.stats.summary())
        for warning in result.warnings:
            print(f"warning: {warning}", file=sys.stderr)
        image, pass_images = result.image, result.passes
        if region is not None:  # the part rendered, alone
            x, y, w, h = region
            image = image[y : y + h, x : x + w]
            pass_images = {name: p[y : y + h, x : x + w] for name, p in pass_images.items()}
        write_whole(image, target, label, pass_images, crypto_names(call.scene))
        print(f"wrote {target}")
    return 0


def _target(script: Path, output: Path | None, call) -> tuple[Path, str]:
    """Where a call's picture goes, and how the user named it, for messages."""
    if output is not None:
        return output, f"-o {output}"
    return call.output, f"{script.name}: gr.render's file {call.output}"


def _tile_bar():
    bar = _progress_bar("tiles")
    return lambda tile, pixels, done, total: bar(done, total)


def _progress_bar(unit: str):
    """A progress bar on stderr, redrawn in a terminal; a log gets the half-way mark and the
    end, not a line per step. Returns a function of (done, total)."""
    start = time.perf_counter()
    interactive = sys.stderr.isatty()

    def show(done, total):
        if not interactive and done not in (total, (total + 1) // 2):
            return
        filled = BAR_WIDTH * done // total
        bar = "#" * filled + "." * (BAR_WIDTH - filled)
        end = "\n" if done == total or not interactive else ""
        elapsed = time.perf_counter() - start
        start_of_line = "\r" if interactive else ""
        print(f"{start_of_line}[{bar}] {done:,}/{total:,} {unit} {elapsed:.1f} s", end=end,
              file=sys.stderr)  # fmt: skip

    return show
