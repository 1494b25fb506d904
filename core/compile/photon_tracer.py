"""Tracing the photon pass's photons (core.kernels.photons) on the render's threads, the same
photons whatever the threads.

A count is shared among the rows (light, caster hull) by the power each sends (`shares`),
then cut into parts of about 1 / PARTS of the pass (`photon_parts`): between parts the
progress is shown and a cancel is heard. Each part is traced by one thread into arrays of
its own, with room for STORED_PER_PHOTON stored photons a photon of the part, and the parts'
photons are joined in the parts' order: which thread traced a part, and when, changes no
photon, its place or its power. The kernels run without the GIL, so two threads trace
twice as fast.
"""

from __future__ import annotations

from concurrent.futures import FIRST_COMPLETED, ThreadPoolExecutor, wait
from queue import Empty, SimpleQueue
from typing import NamedTuple

import numpy as np

from ..kernels.photons import TALLY_DROPPED, TALLY_SLOTS, TALLY_STORED, trace_photons
from ..kernels.workspace import new_workspace
from ..threads import available_threads

STORED_PER_PHOTON = 2  # room for stored photons, per photon of a part
# The pass is traced in about this many parts (of at least PART_PHOTONS photons)
PARTS, PART_PHOTONS = 32, 2048


class Traced(NamedTuple):
    traced: int
    stored: int
    dropped: int  # found no room (at most STORED_PER_PHOTON a photon of its part)
    position: np.ndarray  # float64 (stored, 3)
    direction: np.ndarray  # float64 (stored, 3): the way each arrived
    power: np.ndarray  # float64 (stored, 3)


class PhotonTracer:
    """Traces a count of photons shared among `rows` (light, hull) by `power`, the pilot's
    and the pass's budget alike, on RenderSettings.threads threads (0: the machine's)."""

    def __init__(self, packed, settings, branches, casters, containing, rows, power):
        self.packed, self.settings, self.branches = packed, settings, branches
        self.casters, self.containing = casters, containing
        self.rows, self.power = rows, power
        self.threads = max(1, settings.threads or available_threads())
        self.workspaces: SimpleQueue = SimpleQueue()  # one a thread tracing, made as needed

    def __call__(self, count: int, on_photons=None, should_cancel=None) -> Traced | None:
        """The photons, or None once should_cancel() says True between parts."""
        share = shares(count, self.power)
        plan = np.column_stack([self.rows[:, :2], share])[share > 0]
        total = int(share.sum())
        parts = photon_parts(plan, total)
        traced: list = [None] * len(parts)
        if should_cancel is not None and should_cancel():
            return None
        workers = max(1, min(self.threads, len(parts)))
        with ThreadPoolExecutor(max_workers=workers, thread_name_prefix="whitted-photons") as pool:
            waiting = iter(enumerate(parts))
            running: dict = {}

            def start_next() -> None:
                index, part = next(waiting, (None, None))
                if part is not None:
                    running[pool.submit(self._trace_part, part)] = index

            for _ in range(workers):  # at most one part a thread in flight
                start_next()
            done = 0
            while running:
                finished, _ = wait(running, return_when=FIRST_COMPLETED)
                for future in finished:
                    index = running.pop(future)
                    traced[index] = future.result()
                    done += int(parts[index][:, 5].sum())
                if on_photons is not None:
                    on_photons(done, total)
                if should_cancel is not None and should_cancel():
                    return None  # the parts in flight end first (leaving the pool waits)
                for _ in finished:
                    start_next()
        return _joined(total, traced)

    def _trace_part(self, part: np.ndarray):
        """(positions, directions, powers, tally) of one part's stored photons."""
        room = STORED_PER_PHOTON * int(part[:, 5].sum())
        position, direction, power = (np.zeros((room, 3)) for _ in range(3))
        tally = np.zeros(TALLY_SLOTS, np.int64)
        workspace = self._workspace()
        try:
            stored = _traced(self.packed, self.settings, self.branches, self.casters,
                             self.containing, part, False, position, direction, power,
                             workspace, tally)  # fmt: skip
        finally:
            self.workspaces.put(workspace)
        return position[:stored], direction[:stored], power[:stored], tally

    def _workspace(self):
        try:
            return self.workspaces.get_nowait()
        except Empty:  # none free: a thread's first part
            return new_workspace(0)


def row_power(packed, settings, branches, casters, containing, rows: np.ndarray) -> np.ndarray:
    """The mean power (over RGB) each row (light, hull, photons) of `rows` sends into its
    hull, estimated from the row's photons (numbered by the row's place), measured by the
    tracing kernel itself (core.kernels.photons.trace_photons: one compile for both)."""
    count = len(rows)
    plan = np.column_stack([rows, np.arange(count), np.zeros(count, np.int64), rows[:, 2]])
    power = np.zeros((count, 3))
    none = np.zeros((0, 3))
    _traced(packed, settings, branches, casters, containing, plan, True, none, none, power,
            new_workspace(0), np.zeros(TALLY_SLOTS, np.int64))  # fmt: skip
    return power[:, 0].copy()


def _traced(packed, settings, branches, casters, containing, plan, measure, position, direction,
            power, workspace, tally) -> int:  # fmt: skip
    """trace_photons over `plan` with the render's settings (the one place that calls it,
    so that measuring and tracing pass the same types: one compile)."""
    geo, surf, mats, lights = packed.geometry, packed.surfaces, packed.materials, packed.lights
    return trace_photons(geo, surf, mats, lights, casters, containing, plan, settings.seed,
                         branches, max(settings.max_depth, 1), settings.glossy_samples > 0,
                         measure, position, direction, power, workspace.stacks,
                         workspace.shader_stack, workspace.lobes, tally)  # fmt: skip


def _joined(total: int, traced: list) -> Traced:
    """The parts' photons in the parts' order."""
    tally = np.sum([t[3] for t in traced], axis=0) if traced else np.zeros(TALLY_SLOTS, np.int64)
    arrays = [np.concatenate([t[a] for t in traced]) if traced else np.zeros((0, 3))
              for a in range(3)]  # fmt: skip
    return Traced(total, int(tally[TALLY_STORED]), int(tally[TALLY_DROPPED]), *arrays)


def shares(count: int, power: np.ndarray) -> np.ndarray:
    """int64: `count` photons shared among rows by their power, summing to `count` exactly
    (each row's share rounded down, the rest given to the largest remainders, in order):
    the summary's count is the count the budget set."""
    exact = count * power / power.sum()
    share = np.floor(exact).astype(np.int64)
    rest = count - int(share.sum())
    if rest > 0:
        share[np.argsort(-(exact - share), kind="stable")[:rest]] += 1
    return share


def photon_parts(plan: np.ndarray, total: int) -> list[np.ndarray]:
    """The rows (light, hull, photons) of `plan` as trace_photons' parts: rows (light, hull,
    photons, the row's number, first, count), each part about total / PARTS photons."""
    size = max(PART_PHOTONS, -(-total // PARTS))
    pieces = [
        (light, k, n, number, first, min(size, n - first))
        for number, (light, k, n) in enumerate(plan.tolist())
        for first in range(0, n, size)
    ]
    parts, part, held = [], [], 0
    for piece in pieces:  # small rows share a part
        part.append(piece)
        held += piece[5]
        if held >= size:
            parts.append(np.array(part, np.int64))
            part, held = [], 0
    if part:
        parts.append(np.array(part, np.int64))
    return parts
