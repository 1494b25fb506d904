"""The automatic photon budget: as many caustic photons as the caustics the camera sees need,
from a pilot pass (core.compile.caustics), and no more than the rest of the render costs.

The gather (core.kernels.caustics) spreads each photon over a disk holding k = sqrt(m) of
the m photons stored, so with N photons traced:

- its noise is about 1 / sqrt(k): under NOISE (5%) takes k >= 1 / NOISE^2 = 400, that is
  m >= 160,000 photons stored, whatever the caustic's size;
- its blur is the disk's radius, which on the screen shrinks as sqrt(k / m), that is as
  N^(-1/4): the pilot's photons, projected into the full frame (its border and the farm's
  split play no part, so every piece of a picture gets the same photons), give the disks'
  median radius in pixels at the pilot's count, and the budget is the N that brings it
  under BLUR_PIXELS. A caustic that fills the frame needs more photons than a glint.

The budget is the larger of the two, at least FEWEST (a pass of well under a second, so
that a small picture's caustic is not starved), and at most PHOTONS_PER_RAY photons per
camera ray of the full frame (the pass then costs no more than the rest of the render:
tests/benchmarks/bench_caustics) and the settings' caustic_photons_max. Where no pilot
photon lands in the frame (the caustic is out of sight, or only seen in a mirror) FEWEST
are traced. The count is rounded up to two significant figures, to read well in the
summary, but not past the caps (320 x 320 camera rays give 102,400, not 110,000).
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np

from ..kernels.options import OPTION_PROJECTION, PROJECTION_ORTHOGRAPHIC
from .photon_grid import neighbour_distances, neighbours_wanted

PILOT_PHOTONS = 8192  # traced by the pilot pass, shared among the rows as the budget is
NOISE = 0.05
BLUR_PIXELS = 4.0
FEWEST = 25_000
PHOTONS_PER_RAY = 1.0
SEEN_FEWEST = 16  # pilot photons in the frame below which the caustic counts as unseen


class Budget(NamedTuple):
    photons: int  # to trace
    pilot_seen: int  # pilot photons stored inside the frame
    blur_pixels: float  # the pilot's median disk radius in pixels, scaled to `photons`
    reason: str  # which rule set it: "noise", "blur", "fewest", "camera rays", "most"


def screen_points(frame, width: int, height: int, position: np.ndarray) -> np.ndarray:
    """float64 (n, 2): the pixel coordinates (x right, y down, from the frame's top left) of
    the points in `position` (n, 3) that lie in the full frame, in front of the camera."""
    eye, forward, right, up = (np.asarray(row, float) for row in frame.camera)
    offset = position - eye
    depth = offset @ forward  # along the view (forward is a unit vector)
    across = offset @ right / (right @ right)
    along = offset @ up / (up @ up)
    if frame.options[OPTION_PROJECTION] != PROJECTION_ORTHOGRAPHIC:
        with np.errstate(divide="ignore", invalid="ignore"):
            across, along = across / depth, along / depth  # forward: one unit along the view
    seen = (depth > 0.0) & (np.abs(across) <= 1.0) & (np.abs(along) <= 1.0)
    x = (across[seen] + 1.0) / 2.0 * width
    y = (1.0 - along[seen]) / 2.0 * height
    return np.column_stack([x, y])


def _blur_at(photons: float, pilot_radius: float, pilot_k: float, pilot: int, stored_share):
    """The median disk radius in pixels with `photons` traced: sqrt(k / m) from the pilot's.
    The bisection tries counts down to one photon, so a sharp glint's would store none: a
    disk holds one fellow at least (k = 1 of 2 stored)."""
    k = neighbours_wanted(max(int(stored_share * photons), 2))
    return pilot_radius * math.sqrt(k / pilot_k * pilot / photons)


def _two_figures(count: float) -> int:
    """`count` rounded up to two significant figures."""
    if count < 100:
        return int(math.ceil(count))
    step = 10 ** (int(math.floor(math.log10(count))) - 1)
    return int(math.ceil(count / step - 1e-9) * step)


def automatic_budget(frame, settings, pilot_position: np.ndarray, pilot_traced: int) -> Budget:
    """The budget (module docstring) from the pilot pass's stored positions."""
    rays = settings.width * settings.height * settings.pixel_samples**2
    ceiling = min(settings.caustic_photons_max, max(FEWEST, int(PHOTONS_PER_RAY * rays)))
    floor = min(FEWEST, settings.caustic_photons_max)
    seen = screen_points(frame, settings.width, settings.height, pilot_position)
    if len(seen) < SEEN_FEWEST or pilot_traced == 0:
        return Budget(floor, len(seen), math.nan, "fewest")
    stored_share = len(pilot_position) / pilot_traced
    noise = (1.0 / NOISE**2) ** 2 / stored_share  # k = sqrt(m) >= 1 / NOISE^2
    flat = np.column_stack([seen, np.zeros(len(seen))])
    pilot_k = neighbours_wanted(len(seen))  # as neighbour_distances holds them
    pilot_radius = float(np.median(neighbour_distances(flat)))

    def blur(n):
        return _blur_at(n, pilot_radius, pilot_k, pilot_traced, stored_share)

    low, high = 1.0, float(max(ceiling, FEWEST)) * 1e3
    if blur(high) > BLUR_PIXELS:
        sharp = high
    else:  # the blur falls as the count grows: bisect on its logarithm
        for _ in range(60):
            middle = math.sqrt(low * high)
            low, high = (middle, high) if blur(middle) > BLUR_PIXELS else (low, middle)
        sharp = high
    need = max(noise, sharp)
    reason = "noise" if noise >= sharp else "blur"
    if need < floor:
        need, reason = floor, "fewest"
    if need > ceiling:
        need = ceiling
        reason = "most" if ceiling == settings.caustic_photons_max else "camera rays"
    photons = min(_two_figures(need), ceiling)  # rounded, but never past the caps
    return Budget(photons, len(seen), blur(photons), reason)
