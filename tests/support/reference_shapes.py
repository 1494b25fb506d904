"""World-space references for the shapes, written apart from the kernels.

The convex shapes are described as the kernels never see them: in world space, as a quadric
inequality x^T Q x <= 0 and/or half-spaces a . x <= 0 (homogeneous x), with Q and a carried
through the transform (Q' = T^-T Q T^-1, a' = a T^-1). A ray's inside-interval is the
intersection of the quadric's and the planes' intervals. The torus's quartic is solved with
mpmath at 60 digits.
"""

import math

import mpmath
import numpy as np

OBJECT_QUADRIC = {
    "sphere": np.diag([1.0, 1.0, 1.0, -1.0]),
    "box": None,
    "cylinder": np.diag([1.0, 1.0, 0.0, -1.0]),
    # x^2 + y^2 - ((1 - z) / 2)^2
    "cone": np.array(
        [[1.0, 0, 0, 0], [0, 1.0, 0, 0], [0, 0, -0.25, 0.25], [0, 0, 0.25, -0.25]],
    ),
}
SLAB_Z = [np.array([0, 0, 1.0, -1.0]), np.array([0, 0, -1.0, -1.0])]
OBJECT_PLANES = {
    "sphere": [],
    "box": [
        np.array(row) for row in np.hstack([np.vstack([np.eye(3), -np.eye(3)]), -np.ones((6, 1))])
    ],
    "cylinder": SLAB_Z,
    "cone": SLAB_Z,
}


def world_constraints(kind, world_from_object):
    inverse = np.linalg.inv(world_from_object)
    q = OBJECT_QUADRIC[kind]
    quadric = None if q is None else inverse.T @ q @ inverse
    planes = [a @ inverse for a in OBJECT_PLANES[kind]]
    return quadric, planes


def _intersect(intervals, lo, hi, label_lo, label_hi):
    out = []
    for a, la, b, lb in intervals:
        na, nla = (a, la) if a >= lo else (lo, label_lo)
        nb, nlb = (b, lb) if b <= hi else (hi, label_hi)
        if na <= nb:
            out.append((na, nla, nb, nlb))
    return out


def inside_intervals(quadric, planes, origin, direction):
    """Intervals (t0, label0, t1, label1) of the ray inside the solid; labels say which
    constraint bounds each end ('q' or a plane index), with the margin of the nearest
    competing constraint, for skipping ambiguous rays."""
    o, d = np.append(origin, 1.0), np.append(direction, 0.0)
    intervals = [(-math.inf, None, math.inf, None)]
    for k, a in enumerate(planes):
        ao, ad = a @ o, a @ d
        if ad == 0.0:
            if ao > 0:
                return []
            continue
        t = -ao / ad
        intervals = _intersect(
            intervals, *((-math.inf, t, None, k) if ad > 0 else (t, math.inf, k, None))
        )
    if quadric is not None:
        qa, qb, qc = d @ quadric @ d, o @ quadric @ d, o @ quadric @ o
        disc = qb * qb - qa * qc
        pieces = []
        if qa > 0 and disc >= 0:
            r = math.sqrt(disc)
            pieces = [((-qb - r) / qa, (-qb + r) / qa)]
        elif qa < 0:
            if disc < 0:
                pieces = [(-math.inf, math.inf)]
            else:
                r = math.sqrt(disc)
                t0, t1 = sorted(((-qb - r) / qa, (-qb + r) / qa))
                pieces = [(-math.inf, t0), (t1, math.inf)]
        result = []
        for lo, hi in pieces:
            result += _intersect(intervals, lo, hi, "q", "q")
        intervals = result
    return intervals


def first_crossing(quadric, planes, origin, direction):
    """(t, label) of the first crossing with t > 0, or None."""
    best = None
    for t0, l0, t1, l1 in inside_intervals(quadric, planes, origin, direction):
        for t, label in ((t0, l0), (t1, l1)):
            if t > 0 and (best is None or t < best[0]):
                best = (t, label)
    return best


def constraint_normal(quadric, planes, label, point):
    x = np.append(point, 1.0)
    g = (quadric @ x)[:3] if label == "q" else planes[label][:3]
    return g / np.linalg.norm(g)


def torus_roots_mp(origin, direction, major, minor, digits=60):
    """Real roots t of the torus quartic along an object-space ray, sorted, with the smallest
    distance between any two roots (real or complex) as a measure of nearness to tangency."""
    with mpmath.workdps(digits):
        o = [mpmath.mpf(float(x)) for x in origin]
        d = [mpmath.mpf(float(x)) for x in direction]
        big2, small2 = mpmath.mpf(major) ** 2, mpmath.mpf(minor) ** 2
        dd = sum(x * x for x in d)
        od = sum(a * b for a, b in zip(o, d, strict=True))
        oo = sum(x * x for x in o)
        k = oo + big2 - small2
        exy = d[0] ** 2 + d[1] ** 2
        fxy = 2 * (o[0] * d[0] + o[1] * d[1])
        gxy = o[0] ** 2 + o[1] ** 2
        # (dd t^2 + 2 od t + k)^2 - 4 R^2 (exy t^2 + fxy t + gxy)
        coeffs = [
            k * k - 4 * big2 * gxy,
            4 * od * k - 4 * big2 * fxy,
            4 * od * od + 2 * dd * k - 4 * big2 * exy,
            4 * dd * od,
            dd * dd,
        ]
        roots = mpmath.polyroots(coeffs, maxsteps=400, extraprec=400, asc=True)
        scale = mpmath.sqrt(dd) / (major + minor)
        real = sorted(float(r.real) for r in roots if abs(r.imag) * scale < mpmath.mpf(10) ** -30)
        gap = min(
            (float(abs(a - b) * scale) for i, a in enumerate(roots) for b in roots[i + 1 :]),
            default=math.inf,
        )
        return real, gap


def random_affine(rng, translate=50.0):
    """Rotation times non-uniform scale (0.2..5), translated."""
    q, _ = np.linalg.qr(rng.normal(size=(3, 3)))
    m = np.eye(4)
    m[:3, :3] = q @ np.diag(rng.uniform(0.2, 5.0, size=3))
    m[:3, 3] = rng.uniform(-translate, translate, size=3)
    return m
