"""Where caustic photons start: the convex hulls of the shapes that reflect or refract
(core.kernels.photons), each a sphere or a box, a row of (k, 7) float64 `casters`:

    [HULL_SPHERE, centre x y z, radius, 0, 0]   or   [HULL_BOX, low x y z, high x y z]

An analytic sphere is its own hull (its box's sphere is sqrt(3) as wide); every other shape
has its world box (a thin mirror's box is thin, so a lamp beside the mirror lies outside it,
where a sphere round the mirror would hold the lamp and send it no photon). Every light ray
that enters a convex hull crosses its surface once, so the power entering a hull is the
irradiance over its surface (core.kernels.photons' estimate).

A start point is drawn with a density proportional to the cosine between the surface's
normal and `axis` (towards the light's centre): under a sun every photon then carries the
same power. A light of some extent (an area light, a sphere with a radius, a sun with an
angle) also lights points whose normal faces away from `axis` (a 3 m area light over a ball
lights a band below its equator; a box's sides): for those lights a share of the points is
drawn uniformly over the whole hull instead, the density being the mixture of the two
(`start_density`), so that every point any light ray enters by can be drawn (a glass ball's
box hull under a 3 m area light had lost 0.6% of its caustic through its sides).

A light whose centre lies inside a hull (a lamp in a glass globe) lights it from within:
every ray it sends leaves the hull once, through a point drawn uniformly over the whole
surface (`hull_point`), and the photon starts at the light itself (core.kernels.photons).
`containing` (lights, hulls) marks those pairs, and a light ray counts every hull that holds
its light as one that samples it (`hulls_entered`).
"""

import math

from ..jit.decorators import kernel
from .light_samples import in_frame

HULL_SPHERE, HULL_BOX = 0, 1


@kernel
def _sphere_start(casters, k, axis, a, b):
    """Uniform over the disk the sphere shows along `axis`, lifted onto its hemisphere."""
    ring = math.sqrt(a)
    phi = 2.0 * math.pi * b
    z = math.sqrt(max(0.0, 1.0 - a))
    n = in_frame(axis, ring * math.cos(phi), ring * math.sin(phi), z)
    rho = casters[k, 4]
    x = (casters[k, 1] + rho * n[0], casters[k, 2] + rho * n[1], casters[k, 3] + rho * n[2])
    return x, n, z / (math.pi * rho * rho)


@kernel
def _face_area(casters, k, axis_index):
    """The area of the box's faces normal to axis `axis_index`."""
    e0 = casters[k, 4] - casters[k, 1]
    e1 = casters[k, 5] - casters[k, 2]
    e2 = casters[k, 6] - casters[k, 3]
    if axis_index == 0:
        return e1 * e2
    if axis_index == 1:
        return e0 * e2
    return e0 * e1


@kernel
def _box_start(casters, k, axis, a, b, pick):
    """A face chosen by its area seen along `axis` (its area times the cosine), then a
    uniform point of it: density cos / (the box's whole area seen along axis)."""
    seen = 0.0
    for i in range(3):
        seen += _face_area(casters, k, i) * abs(axis[i])
    if seen <= 0.0:
        return (0.0, 0.0, 0.0), (0.0, 0.0, 1.0), 0.0
    chosen = 0
    running = 0.0
    for i in range(3):
        running += _face_area(casters, k, i) * abs(axis[i])
        if pick * seen < running or i == 2:
            chosen = i
            break
    # the face towards the axis: the high side if the axis points up that coordinate
    side = 1.0 if axis[chosen] > 0.0 else -1.0
    lo = (casters[k, 1], casters[k, 2], casters[k, 3])
    hi = (casters[k, 4], casters[k, 5], casters[k, 6])
    if chosen == 0:
        x = (hi[0] if side > 0.0 else lo[0], lo[1] + a * (hi[1] - lo[1]),
             lo[2] + b * (hi[2] - lo[2]))  # fmt: skip
        n = (side, 0.0, 0.0)
    elif chosen == 1:
        x = (lo[0] + a * (hi[0] - lo[0]), hi[1] if side > 0.0 else lo[1],
             lo[2] + b * (hi[2] - lo[2]))  # fmt: skip
        n = (0.0, side, 0.0)
    else:
        x = (lo[0] + a * (hi[0] - lo[0]), lo[1] + b * (hi[1] - lo[1]),
             hi[2] if side > 0.0 else lo[2])  # fmt: skip
        n = (0.0, 0.0, side)
    return x, n, abs(axis[chosen]) / seen


@kernel
def hull_start(casters, k, axis, a, b, pick):
    """(point, outward unit normal, density per unit area) of a photon's start on hull k,
    for the light towards unit `axis` (the module's rule); (a, b, pick) uniform in [0, 1)."""
    if casters[k, 0] == HULL_SPHERE:
        return _sphere_start(casters, k, axis, a, b)
    return _box_start(casters, k, axis, a, b, pick)


@kernel
def start_density(casters, k, axis, n, facing_share):
    """The density per unit area of a start at a point of normal n (a sphere's radial, a
    box face's own) of hull k when a share `facing_share` is drawn by `hull_start` and the
    rest by `hull_point`."""
    if casters[k, 0] == HULL_SPHERE:
        rho = casters[k, 4]
        cos = n[0] * axis[0] + n[1] * axis[1] + n[2] * axis[2]
        facing = max(cos, 0.0) / (math.pi * rho * rho)
        whole = 4.0 * math.pi * rho * rho
    else:
        seen, whole, facing = 0.0, 0.0, 0.0
        for i in range(3):
            seen += _face_area(casters, k, i) * abs(axis[i])
            whole += 2.0 * _face_area(casters, k, i)
        for i in range(3):
            if n[i] * axis[i] > 0.0 and seen > 0.0:
                facing = abs(axis[i]) / seen
        if whole <= 0.0:
            return 0.0
    return facing_share * facing + (1.0 - facing_share) / whole


@kernel
def hull_point(casters, k, a, b, pick):
    """(point, outward unit normal, density per unit area) uniform over hull k's whole
    surface, for a light inside it; (a, b, pick) uniform in [0, 1)."""
    if casters[k, 0] == HULL_SPHERE:
        z = 1.0 - 2.0 * a
        ring = math.sqrt(max(0.0, 1.0 - z * z))
        phi = 2.0 * math.pi * b
        n = (ring * math.cos(phi), ring * math.sin(phi), z)
        rho = casters[k, 4]
        x = (casters[k, 1] + rho * n[0], casters[k, 2] + rho * n[1], casters[k, 3] + rho * n[2])
        return x, n, 1.0 / (4.0 * math.pi * rho * rho)
    whole = 0.0
    for i in range(3):
        whole += 2.0 * _face_area(casters, k, i)
    if whole <= 0.0:
        return (0.0, 0.0, 0.0), (0.0, 0.0, 1.0), 0.0
    # a face by its area (each axis's two faces, the pick's halves), then a uniform point
    running, chosen, side = 0.0, 2, 1.0
    for i in range(3):
        share = 2.0 * _face_area(casters, k, i)
        if pick * whole < running + share:
            chosen = i
            side = 1.0 if pick * whole < running + 0.5 * share else -1.0
            break
        running += share
    axis = (1.0 if chosen == 0 else 0.0, 1.0 if chosen == 1 else 0.0, 1.0 if chosen == 2 else 0.0)
    x, n, _ = _box_start(casters, k, (side * axis[0], side * axis[1], side * axis[2]), a, b, 0.0)
    return x, n, 1.0 / whole


@kernel
def hull_centre(casters, k):
    if casters[k, 0] == HULL_SPHERE:
        return casters[k, 1], casters[k, 2], casters[k, 3]
    return (
        0.5 * (casters[k, 1] + casters[k, 4]),
        0.5 * (casters[k, 2] + casters[k, 5]),
        0.5 * (casters[k, 3] + casters[k, 6]),
    )


@kernel
def _entry(casters, k, o, d):
    """Where the line o + s d (d unit) enters hull k, or inf if it does not."""
    if casters[k, 0] == HULL_SPHERE:
        gap = (casters[k, 1] - o[0], casters[k, 2] - o[1], casters[k, 3] - o[2])
        along = gap[0] * d[0] + gap[1] * d[1] + gap[2] * d[2]
        off2 = gap[0] * gap[0] + gap[1] * gap[1] + gap[2] * gap[2] - along * along
        rho = casters[k, 4]
        if off2 >= rho * rho:
            return math.inf
        return along - math.sqrt(rho * rho - off2)
    near, far = -math.inf, math.inf
    for i in range(3):
        lo, hi = casters[k, 1 + i], casters[k, 4 + i]
        if d[i] == 0.0:
            if o[i] < lo or o[i] > hi:
                return math.inf
            continue
        t0, t1 = (lo - o[i]) / d[i], (hi - o[i]) / d[i]
        near = max(near, min(t0, t1))
        far = min(far, max(t0, t1))
    return near if near <= far else math.inf


@kernel
def hulls_entered(casters, containing, light, o, d, s_low, s_high):
    """How many hulls sample the light ray o + s d (d unit), s from s_low (the light) to
    s_high (its first hit): those it enters in [s_low, s_high), and those that hold the
    light (`containing[light]`), which every ray of it leaves."""
    count = 0
    for k in range(casters.shape[0]):
        if containing[light, k]:
            count += 1
            continue
        entry = _entry(casters, k, o, d)
        if s_low <= entry < s_high:
            count += 1
    return count
