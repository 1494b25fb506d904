"""`python -m core farm`: the command line of a farm job (see core.farm)."""

from __future__ import annotations

import argparse
import shlex
import sys
from pathlib import Path

from .jobs import LAST_FRAME, FarmError, frame_path, parse_frames, parse_split

# A local cluster's worker processes, and a task's render threads: far past any machine's
# cores, short of what would exhaust its processes or memory before a message could be given
MAX_LOCAL_WORKERS = 256
MAX_THREADS = 1024


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument(
        "scene",
        type=Path,
        help="the .blend file or .lua script, as the "
        "workers see it (a shared folder, or the same path on every host)",
    )
    parser.add_argument(
        "-o", "--output", required=True, help="the frames' files, Blender's way: out_####.png"
    )
    parser.add_argument(
        "--scheduler",
        default="local",
        help="tcp://HOST:8786 (a running `dask scheduler`), or 'local': a "
        "cluster of worker processes on this machine (default)",
    )
    parser.add_argument(
        "--split",
        type=_split,
        default=(1, 1),
        metavar="COLSxROWS",
        help="render each frame as this many borders, a task each (4x4)",
    )
    parser.add_argument(
        "--frames",
        type=_frames,
        default=None,
        metavar="LIST",
        help="frames to render, such as 1-250, or scene for its frame range (default: the "
        "current frame, as F12 renders it)",
    )
    parser.add_argument(
        "--chunk",
        type=_count("--chunk", 1, 2 * LAST_FRAME + 1),
        default=1,
        metavar="N",
        help="frames per task when frames are not split (default 1)",
    )
    parser.add_argument(
        "--workers",
        type=_count("--workers", 0, MAX_LOCAL_WORKERS),
        default=0,
        metavar="N",
        help="worker processes of a local cluster (default: one per core)",
    )
    parser.add_argument(
        "--threads",
        type=_count("--threads", 0, MAX_THREADS),
        default=1,
        metavar="N",
        help="render threads per task (default 1: one task per core)",
    )
    parser.add_argument(
        "--blender",
        default="blender",
        metavar="COMMAND",
        help="how workers start Blender, e.g. '/opt/blender/blender' or "
        "'blender --python-use-system-env' (default: blender)",
    )
    parser.add_argument(
        "--fresh-blender",
        action="store_true",
        help="start a blender -b for every task and stop it after, as a farm manager "
        "would (default: each worker keeps its Blender running, the scene open, between "
        "tasks, and a task costs only its render)",
    )
    parser.add_argument("--addon", default="whitted",
                        help="the add-on's module name in the workers' Blender (default "
                        "whitted; an extension is bl_ext.user_default.whitted)")  # fmt: skip


def _count(option: str, low: int, high: int):
    """An argparse type: a whole number from low to high, refused in the option's terms."""

    def parse(text: str) -> int:
        try:
            value = int(text.strip())
        except ValueError:
            value = None
        if value is None or not low <= value <= high:
            raise argparse.ArgumentTypeError(
                f"got {text[:40]!r}; give a whole number from {low} to {high:,}"
            )
        return value

    parse.__name__ = option
    return parse


def _split(text: str):
    try:
        return parse_split(text)
    except FarmError as error:
        raise argparse.ArgumentTypeError(str(error)) from None


def _frames(text: str):
    if text.strip() == "scene":
        return "scene"
    try:
        return parse_frames(text)
    except FarmError as error:
        raise argparse.ArgumentTypeError(str(error)) from None


def run(args) -> int:
    from ..output_file import OutputError, check_writable

    if not args.scene.is_file():
        print(f"error: {args.scene}: no such scene file", file=sys.stderr)
        return 1
    try:  # before any cluster starts: a folder that cannot take the frames
        check_writable(frame_path(args.output, 1), f"-o {args.output}")
    except OutputError as error:
        print(f"error: {error}", file=sys.stderr)
        return 1
    try:
        from .client import Job, run_job
    except ImportError as error:  # distributed is the farm command's alone
        print(f"error: the farm needs Dask's distributed ({error.name} is missing): "
              "pip install 'distributed==2026.8.0'", file=sys.stderr)  # fmt: skip
        return 1
    job = Job(
        scene=args.scene, output=args.output, scheduler=args.scheduler, split=args.split,
        frames=args.frames, chunk=args.chunk, blender=tuple(shlex.split(args.blender)),
        workers=args.workers, threads=args.threads, addon=args.addon,
        fresh_blender=args.fresh_blender,
    )  # fmt: skip
    from ..cs488 import ScriptError

    try:
        report = run_job(job, say=lambda line: print(line, flush=True))
    except (FarmError, ScriptError) as error:
        print(f"error: {error}", file=sys.stderr)
        return 1
    except KeyboardInterrupt:
        print("\ninterrupted: every task cancelled; unfinished frames not written",
              file=sys.stderr)  # fmt: skip
        return 130
    frames = len(report.written)
    print(f"Farm: {frames} frame{'s' * (frames != 1)} in {report.wall_s:.1f} s on "
          f"{report.workers} workers, busiest worker {report.busiest_worker_s:.1f} s")  # fmt: skip
    return 0
