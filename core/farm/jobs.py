"""A farm job as tasks: borders of a frame in whole pixels, chunks of frames, and the names
Blender gives frames. No Dask here: the plan is plain data, tested on its own."""

from __future__ import annotations

import bisect
import itertools
import re
from dataclasses import dataclass
from pathlib import Path

TASK_KEY_PREFIX = "whitted-"  # of every task's Dask key, the probe's too


class FarmError(Exception):
    """A job that cannot run as asked: bad arguments, a failed task, no scheduler."""


@dataclass(frozen=True)
class Border:
    """A rectangle of the frame in pixels, y from the top row, as core's RenderSettings.region."""

    x: int
    y: int
    width: int
    height: int

    def describe(self) -> str:
        return (f"border x {self.x}-{self.x + self.width - 1}, "
                f"y {self.y}-{self.y + self.height - 1}")  # fmt: skip


@dataclass(frozen=True)
class Task:
    """What one worker renders: frames of the scene, whole or one border of each."""

    scene: str  # the .blend or .lua file, as the workers see it
    frames: tuple[int, ...]
    border: Border | None = None  # in pixels, or None: the whole frame (or `part`'s)
    # (column, row, columns, rows): a border the worker works out from the frame's size, as
    # `borders` cuts it, so that the client need not read the .blend (a Blender start-up)
    part: tuple[int, int, int, int] | None = None
    # the command that starts Blender on the workers ("blender", or the binary and options
    # such as --python-use-system-env), as words
    blender: tuple[str, ...] = ("blender",)
    threads: int = 0  # render threads per task (0: all the worker's cores)

    @property
    def kind(self) -> str:
        return "lua" if self.scene.endswith(".lua") else "blend"

    def describe(self) -> str:
        frames = (f"frame {self.frames[0]}" if len(self.frames) == 1
                  else f"frames {self.frames[0]}-{self.frames[-1]}")  # fmt: skip
        if self.part is not None:
            column, row, columns, rows = self.part
            return f"border {row * columns + column + 1} of {columns * rows} (column " \
                   f"{column + 1}, row {row + 1} from the top) of {frames}"  # fmt: skip
        return frames if self.border is None else f"{self.border.describe()} of {frames}"

    @property
    def key(self) -> str:
        """Dask's key for it: unique in the job, readable on the dashboard."""
        where = "" if self.border is None else f"-{self.border.x}-{self.border.y}"
        if self.part is not None:
            where = f"-part-{self.part[0]}-{self.part[1]}"
        return f"{TASK_KEY_PREFIX}{self.frames[0]}-{self.frames[-1]}{where}"


def parse_split(text: str) -> tuple[int, int]:
    match = re.fullmatch(r"\s*(\d+)\s*[xX]\s*(\d+)\s*", text)
    if not match or int(match[1]) < 1 or int(match[2]) < 1:
        raise FarmError(f"--split {text!r}: give columns x rows, such as 4x4")
    columns, rows = int(match[1]), int(match[2])
    if columns * rows > MAX_PARTS:
        raise FarmError(
            f"--split {text}: {columns * rows:,} borders a frame; at most {MAX_PARTS:,} (256x256)"
        )
    return columns, rows


# Blender's frame numbers run from -1048574 to 1048574 (MINAFRAME, MAXFRAME)
LAST_FRAME = 1_048_574
# The most borders a frame may be cut into: each is a task, and a worker's start-up
MAX_PARTS = 256 * 256


class FrameSet:
    """Frames as runs (first, last), each frame once, in the order given: a set of millions
    of frames costs a pair per run, never a number per frame."""

    def __init__(self, runs: list[tuple[int, int]]):
        self.runs = tuple(runs)

    def __len__(self) -> int:
        return sum(last - first + 1 for first, last in self.runs)

    def __iter__(self):
        for first, last in self.runs:
            yield from range(first, last + 1)

    def __eq__(self, other) -> bool:
        if isinstance(other, FrameSet):
            return self.runs == other.runs
        return isinstance(other, tuple) and len(other) == len(self) and tuple(self) == other

    def __hash__(self) -> int:
        return hash(self.runs)

    def __repr__(self) -> str:
        return f"FrameSet({list(self.runs)})"


def parse_frames(text: str) -> FrameSet:
    """'1-250', '7' or '1-10,20-30' as the frames, each once, in order. Linear in the text's
    runs (a frame listed again is dropped by subtracting the runs kept so far, found by
    bisection), whatever the frames' count."""
    kept: list[tuple[int, int]] = []  # the runs kept so far, sorted and disjoint
    ordered: list[tuple[int, int]] = []
    for part in text.split(","):
        match = re.fullmatch(r"\s*(-?\d{1,12})\s*(?:-\s*(-?\d{1,12})\s*)?", part)
        if not match:
            raise FarmError(f"--frames {text!r}: give frames as 1-250, 7, or 1-10,20-30")
        first = int(match[1])
        last = int(match[2]) if match[2] is not None else first
        if last < first:
            raise FarmError(f"--frames {text!r}: {first}-{last} runs backwards")
        if not -LAST_FRAME <= first <= last <= LAST_FRAME:
            raise FarmError(
                f"--frames {text!r}: Blender's frames run from {-LAST_FRAME} to {LAST_FRAME}"
            )
        ordered += _cover(kept, first, last)
    return FrameSet(_joined(ordered))


def _cover(kept: list[tuple[int, int]], first: int, last: int) -> list[tuple[int, int]]:
    """The parts of first..last that no run in `kept` covered; `kept` (sorted, disjoint, no
    two adjacent) then covers first..last too, its runs there merged into one, so that each
    run is passed over once however the list repeats itself."""
    start = max(0, bisect.bisect_left(kept, (first, first)) - 1)
    if start < len(kept) and kept[start][1] < first - 1:
        start += 1  # ends before first..last, with a gap: not touched
    pieces, at, end = [], first, start
    low, high = first, last
    while end < len(kept) and kept[end][0] <= last + 1:
        run_first, run_last = kept[end]
        if run_first > at:
            pieces.append((at, min(run_first - 1, last)))
        at = max(at, run_last + 1)
        low, high = min(low, run_first), max(high, run_last)
        end += 1
    if at <= last:
        pieces.append((at, last))
    kept[start:end] = [(low, high)]
    return [piece for piece in pieces if piece[0] <= piece[1]]


def _joined(runs: list[tuple[int, int]]) -> list[tuple[int, int]]:
    """Runs that follow on from one another as one: 1-3,4-6 is 1-6."""
    joined: list[tuple[int, int]] = []
    for first, last in runs:
        if joined and joined[-1][1] + 1 == first:
            joined[-1] = (joined[-1][0], last)
        else:
            joined.append((first, last))
    return joined


def borders(width: int, height: int, columns: int, rows: int) -> list[Border]:
    """The frame cut into columns x rows borders covering every pixel once, row by row
    from the top; sizes differ by at most a pixel."""
    if columns > width or rows > height:
        raise FarmError(
            f"--split {columns}x{rows}: the frame is only {width} x {height} pixels; "
            "split it into fewer parts"
        )
    xs = [width * c // columns for c in range(columns + 1)]
    ys = [height * r // rows for r in range(rows + 1)]
    return [Border(xs[c], ys[r], xs[c + 1] - xs[c], ys[r + 1] - ys[r])
            for r in range(rows) for c in range(columns)]  # fmt: skip


def chunks(frames, size: int):
    """The frames in tuples of `size` (the last may be shorter), made as they are asked for."""
    if size < 1:
        raise FarmError(f"--chunk {size}: give a number of frames per task, at least 1")
    return _chunked(iter(frames), size)


def _chunked(frames, size: int):
    while chunk := tuple(itertools.islice(frames, size)):
        yield chunk


def frame_path(pattern: str | Path, frame: int) -> Path:
    """Blender's naming: the last run of '#' becomes the frame number padded to its length
    ('out_####.png', 7 -> out_0007.png); a name without '#' is used as it is."""
    text = str(pattern)
    runs = list(re.finditer(r"#+", text))
    if not runs:
        return Path(text)
    run = runs[-1]
    return Path(text[: run.start()] + str(frame).zfill(len(run[0])) + text[run.end() :])


class Plan:
    """The tasks of a job, made as they are submitted: per frame, a task per border when the
    split has more than one part, in pixels when the frame's `size` is known, else as parts
    the workers resolve; without a split, a task per chunk of frames. `len` and
    `tasks_of_frame` are known without making any."""

    def __init__(self, scene: str, frames, size: tuple[int, int] | None,
                 split: tuple[int, int], chunk: int, blender: tuple[str, ...] = ("blender",),
                 threads: int = 0):  # fmt: skip
        columns, rows = split
        if columns * rows > MAX_PARTS:
            raise FarmError(
                f"--split {columns}x{rows}: {columns * rows:,} borders a frame; at most "
                f"{MAX_PARTS:,} (256x256)"
            )
        if chunk < 1:
            raise FarmError(f"--chunk {chunk}: give a number of frames per task, at least 1")
        self.scene, self.frames, self.size, self.split = scene, frames, size, split
        self.chunk, self.blender, self.threads = chunk, blender, threads
        self.parts = columns * rows
        self.cut = borders(*size, columns, rows) if self.parts > 1 and size else None

    def __len__(self) -> int:
        frames = len(self.frames)
        return frames * self.parts if self.parts > 1 else -(-frames // self.chunk)

    def tasks_of_frame(self) -> int:
        """How many tasks render each frame (each frame is in one chunk, or in every part)."""
        return self.parts

    def __iter__(self):
        scene, blender, threads = self.scene, self.blender, self.threads
        if self.parts == 1:
            for frames in chunks(self.frames, self.chunk):
                yield Task(scene, frames, None, None, blender, threads)
            return
        columns, rows = self.split
        for frame in self.frames:
            if self.cut is not None:
                for border in self.cut:
                    yield Task(scene, (frame,), border, None, blender, threads)
            else:
                for row in range(rows):
                    for column in range(columns):
                        part = (column, row, columns, rows)
                        yield Task(scene, (frame,), None, part, blender, threads)


def plan(scene: str, frames, size, split, chunk, blender=("blender",), threads=0) -> list[Task]:
    """Every task of a job at once, as a list (Plan makes them one by one)."""
    return list(Plan(scene, frames, size, split, chunk, blender, threads))
