"""The farm job from the submitting side: connect to the scheduler (or start a LocalCluster),
submit a task per border or chunk of frames, report progress, write each frame once all of
it is back, and on Ctrl-C or a failed task cancel everything still running."""

from __future__ import annotations

import contextlib
import os
import shutil
import tempfile
import time
import uuid
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path

from .jobs import TASK_KEY_PREFIX, FarmError, FrameSet, Plan, frame_path
from .stitch import png_bytes, stitch, write_whole
from .worker import TaskError, probe_scene, run_task

CONNECT_TIMEOUT_S = 10
CANCEL_WAIT_S = 5  # for running tasks to stop their renders
# Tasks submitted ahead of those running, per worker: enough to keep every worker busy, few
# enough that a job of a million frames holds a few hundred tasks, not a million
TASKS_AHEAD_PER_WORKER = 4
SCENE_RANGE = "scene"


@dataclass
class Job:
    scene: Path
    output: str  # Blender's naming: out_####.png
    scheduler: str  # tcp://HOST:8786, or "local"
    split: tuple[int, int] = (1, 1)
    # None: the scene's current frame, as F12 renders it; SCENE_RANGE: its frame range (a
    # CS488 script has one image, frame 1)
    frames: tuple[int, ...] | str | None = None
    chunk: int = 1
    blender: tuple[str, ...] = ("blender",)
    workers: int = 0  # of a local cluster (0: one per core)
    threads: int = 1  # render threads per task
    addon: str = "whitted"
    fresh_blender: bool = False  # a Blender per task, not the workers' warm ones


@dataclass
class JobReport:
    written: list[Path] = field(default_factory=list)
    tasks: int = 0
    workers: int = 0
    wall_s: float = 0.0
    rays: float = 0.0
    busiest_worker_s: float = 0.0  # the most task time one worker spent


def connect(scheduler: str, workers: int):
    """(client, cluster or None). A scheduler that cannot be reached is a FarmError."""
    import dask
    from distributed import Client, LocalCluster

    if scheduler == "local":
        count = workers or len(os.sched_getaffinity(0))
        # The workers' scratch space (dask-scratch-space) and temporary files (their tasks',
        # their Blenders') all in one folder of the job's, removed when the cluster closes
        # (the scheduler's, in this process, by Dask's temporary-directory setting)
        folder = tempfile.mkdtemp(prefix="whitted-farm-")
        setting = dask.config.set({"temporary-directory": folder})
        try:
            cluster = LocalCluster(n_workers=count, threads_per_worker=1, processes=True,
                                   dashboard_address=None, local_directory=folder,
                                   env={"TMPDIR": folder})  # fmt: skip
        except BaseException:
            setting.__exit__(None, None, None)
            shutil.rmtree(folder, ignore_errors=True)
            raise
        cluster.whitted_cleanup = (setting, folder)
        client = Client(cluster)
        from .quiet_workers import QuietTaskFailures

        client.register_plugin(QuietTaskFailures())
        return client, cluster
    try:
        return Client(scheduler, timeout=CONNECT_TIMEOUT_S), None
    except (OSError, TimeoutError, ValueError) as error:
        raise FarmError(
            f"--scheduler {scheduler}: cannot reach a Dask scheduler there ({error}); start "
            "one with `dask scheduler` on that host, or use --scheduler local"
        ) from None


def _script_size_and_frames(job: Job) -> tuple[tuple[int, int], tuple[int, ...]]:
    """A CS488 script's frame size, and its one frame: the script runs here, before any
    cluster starts, so that its mistakes are named at once."""
    from ..cs488 import load_script

    calls = load_script(job.scene, print_line=lambda line: None)
    if len(calls) != 1:
        raise FarmError(f"{job.scene.name}: the farm renders scripts that call gr.render once")
    if job.frames not in (None, (1,), SCENE_RANGE):
        raise FarmError(
            f"--frames: {job.scene.name} is a CS488 script, one image (frame 1); "
            "leave --frames out for it"
        )
    settings = calls[0].settings
    return (settings.width, settings.height), (1,)


def _blend_frames(client, job: Job):
    """The frames of a .blend to render (its borders are cut by the workers): reading its
    current frame or frame range costs a Blender start on a worker, done only when
    --frames does not say."""
    if job.frames not in (None, SCENE_RANGE):
        return job.frames
    future = client.submit(probe_scene, str(job.scene.resolve()), job.blender, job.addon,
                           key=f"{TASK_KEY_PREFIX}probe-{uuid.uuid4().hex}")  # fmt: skip
    try:
        width, height, first, last, current = future.result()
    except TaskError as error:
        raise FarmError(str(error)) from None
    if job.frames == SCENE_RANGE:
        return FrameSet([(first, last)])
    return (current,)


def run_job(job: Job, say: Callable[[str], None] = print) -> JobReport:
    """Render `job`; raises FarmError (nothing of the failed frames written) or, on Ctrl-C,
    KeyboardInterrupt after cancelling every task."""
    from distributed import Event, as_completed, wait

    started = time.perf_counter()
    if job.scene.suffix == ".lua":
        size, frames = _script_size_and_frames(job)
    client, cluster = connect(job.scheduler, job.workers)
    try:
        if job.scene.suffix != ".lua":
            size, frames = None, _blend_frames(client, job)
        tasks = Plan(str(job.scene.resolve()), frames, size, job.split, job.chunk, job.blender,
                     job.threads)  # fmt: skip
        if len(tasks) == 0:
            raise FarmError(f"{job.scene.name}: no frames to render (its frame range is empty)")
        if len(frames) > 1 and "#" not in job.output:
            raise FarmError(f"-o {job.output}: name the frames with #### (Blender's convention)")
        workers = len(client.scheduler_info(n_workers=-1)["workers"])
        say(f"Farm: {len(tasks)} tasks on {workers} workers ({next(iter(tasks)).describe()}, ...)")
        cancel = Event(f"whitted-cancel-{uuid.uuid4().hex}", client=client)
        submitting = _Submitter(client, iter(tasks), tasks.tasks_of_frame(), cancel.name, job)
        report = JobReport(tasks=len(tasks), workers=workers)
        try:
            _collect(submitting, size, job, report, started, say, as_completed,
                     ahead=max(1, workers) * TASKS_AHEAD_PER_WORKER)  # fmt: skip
        except BaseException:
            cancel.set()
            # The running tasks see the flag within a poll and end by themselves: waited
            # for, a local cluster's workers then close with nothing in flight. A task not
            # yet polling (its Blender starting, or compiling kernels on a cold cache) is
            # cancelled by force past the wait: Dask's timeout must not hide the cause
            with contextlib.suppress(TimeoutError):
                wait(list(submitting.futures), timeout=CANCEL_WAIT_S)
            client.cancel(list(submitting.futures), force=True)
            raise
        report.wall_s = time.perf_counter() - started
        return report
    finally:
        client.close()
        if cluster is not None:
            cluster.close()
            setting, folder = cluster.whitted_cleanup
            setting.__exit__(None, None, None)
            shutil.rmtree(folder, ignore_errors=True)


class _Submitter:
    """Submits the plan's tasks as room is made for them, and counts each frame's tasks."""

    def __init__(self, client, tasks, tasks_of_frame: int, cancel_name: str, job: Job):
        self.client, self.tasks, self.tasks_of_frame = client, tasks, tasks_of_frame
        self.cancel_name, self.job = cancel_name, job
        self.futures: dict = {}  # in flight -> its task
        self.remaining: dict[int, int] = {}  # frame -> its tasks not yet back

    def next(self):
        """The next task's future, or None when every task is submitted."""
        task = next(self.tasks, None)
        if task is None:
            return None
        for frame in task.frames:  # a frame's tasks follow one another in the plan
            self.remaining.setdefault(frame, self.tasks_of_frame)
        future = self.client.submit(run_task, task, self.cancel_name, self.job.addon,
                                    self.job.fresh_blender, key=task.key, pure=False)  # fmt: skip
        self.futures[future] = task
        return future


def _collect(submitting, size, job, report, started, say, as_completed, ahead: int) -> None:
    first = [f for f in (submitting.next() for _ in range(ahead)) if f is not None]
    remaining = submitting.remaining
    parts: dict[int, dict] = {}
    sizes: dict[int, tuple[int, int]] = {}  # frame -> its size, as the workers found it
    busy: dict[str, float] = {}
    finished = as_completed(first)
    for done, future in enumerate(finished, start=1):
        task = submitting.futures.pop(future)
        try:
            result = future.result()
        except TaskError as error:
            raise FarmError(str(error)) from None
        except Exception as error:  # the scheduler's: a task whose workers kept dying
            raise FarmError(f"{task.describe()}: {type(error).__name__}: {error}") from None
        if result is None:  # the task saw the job's cancel flag
            raise FarmError(f"{task.describe()}: cancelled")
        following = submitting.next()
        if following is not None:
            finished.add(following)
        report.rays += result.rays
        busy[result.worker] = busy.get(result.worker, 0.0) + result.wall_s
        for frame, data in result.frames.items():
            if result.border is None:
                parts[frame] = data
            else:
                parts.setdefault(frame, {})[result.border] = data
                sizes[frame] = result.size or size
            remaining[frame] -= 1
            if remaining[frame] == 0:
                del remaining[frame]
                frame_size = sizes.pop(frame, size)
                report.written.append(_write_frame(job, frame, frame_size, parts.pop(frame), say))
        elapsed = time.perf_counter() - started
        left = elapsed / done * (report.tasks - done)
        say(f"Farm: {done}/{report.tasks} tasks | {report.rays / elapsed / 1e6:.2f} M rays/s "
            f"across workers | about {left:.0f} s left")  # fmt: skip
    report.busiest_worker_s = max(busy.values(), default=0.0)


def _write_frame(job: Job, frame: int, size, data, say) -> Path:
    path = frame_path(job.output, frame)
    if isinstance(data, dict):
        data = png_bytes(stitch(*size, data))
    write_whole(path, data)
    say(f"Saved: '{path}'")
    return path
