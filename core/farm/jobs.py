"""A farm job as tasks: borders of a frame in whole pixels, chunks of frames, and the names
Blender gives frames. No Dask here: the plan is plain data, tested on its own."""

from __future__ import annotations

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
    return int(match[1]), int(match[2])


def parse_frames(text: str) -> tuple[int, ...]:
    """'1-250', '7' or '1-10,20-30' as the frames, each once, in order."""
    frames = []
    for part in text.split(","):
        match = re.fullmatch(r"\s*(-?\d+)\s*(?:-\s*(-?\d+)\s*)?", part)
        if not match:
            raise FarmError(f"--frames {text!r}: give frames as 1-250, 7, or 1-10,20-30")
        first = int(match[1])
        last = int(match[2]) if match[2] is not None else first
        if last < first:
            raise FarmError(f"--frames {text!r}: {first}-{last} runs backwards")
        frames += [f for f in range(first, last + 1) if f not in frames]
    return tuple(frames)


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


def chunks(frames: tuple[int, ...], size: int) -> list[tuple[int, ...]]:
    if size < 1:
        raise FarmError(f"--chunk {size}: give a number of frames per task, at least 1")
    return [frames[i : i + size] for i in range(0, len(frames), size)]


def frame_path(pattern: str | Path, frame: int) -> Path:
    """Blender's naming: the last run of '#' becomes the frame number padded to its length
    ('out_####.png', 7 -> out_0007.png); a name without '#' is used as it is."""
    text = str(pattern)
    runs = list(re.finditer(r"#+", text))
    if not runs:
        return Path(text)
    run = runs[-1]
    return Path(text[: run.start()] + str(frame).zfill(len(run[0])) + text[run.end() :])


def plan(scene: str, frames: tuple[int, ...], size: tuple[int, int] | None,
         split: tuple[int, int], chunk: int, blender: tuple[str, ...] = ("blender",),
         threads: int = 0) -> list[Task]:  # fmt: skip
    """The tasks of a job: per frame, a task per border when the split has more than one
    part, in pixels when the frame's `size` is known, else as parts the workers resolve;
    without a split, a task per chunk of frames."""
    columns, rows = split
    if columns * rows > 1:
        if size is None:
            return [Task(scene, (f,), None, (c, r, columns, rows), blender, threads)
                    for f in frames for r in range(rows) for c in range(columns)]  # fmt: skip
        parts = borders(*size, columns, rows)
        return [Task(scene, (f,), b, None, blender, threads) for f in frames for b in parts]
    return [Task(scene, c, None, None, blender, threads) for c in chunks(frames, chunk)]
