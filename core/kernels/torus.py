"""Ray against torus: the quartic, solved so that it holds at grazing angles and far away.

The torus about the z axis, tube radius r around a circle of radius R, is the zero set of

    f(p) = (|p|^2 + R^2 - r^2)^2 - 4 R^2 (x^2 + y^2).

Along a ray this is a quartic in t. Closed-form (Ferrari) solutions lose most of their digits
when the ray grazes the tube or starts far away, and miss or invent hits. Instead:

1. Near start: the ray is first clipped to the bounding sphere |p| <= R + r, its origin moved
   to where the line enters it (crossings are returned at any t, for CSG), and lengths are
   measured in units of R + r. The coefficients are then all of order one however far away
   the camera is.
2. Root isolation by derivatives: the roots of f'' (a quadratic, in closed form) split the
   segment into pieces where f' is monotonic; the roots of f' found there split it into
   pieces where f is monotonic; each piece holds at most one root of f, bracketed by a sign
   change.
3. Each bracketed root is found by Newton's method safeguarded with bisection, in float64,
   to the last bit: it cannot escape its bracket, so it never converges to the wrong root.

A tangent ray (a double root) is a hit only if rounding leaves a sign change; that is the
unavoidable band around tangency, and it is narrow (tested against extended precision).
"""

import math

from ..jit.decorators import kernel

_MAX_ITERATIONS = 100


@kernel
def _poly4(c, s):
    """c[0] s^4 + c[1] s^3 + c[2] s^2 + c[3] s + c[4], and its derivative."""
    value = (((c[0] * s + c[1]) * s + c[2]) * s + c[3]) * s + c[4]
    slope = ((4.0 * c[0] * s + 3.0 * c[1]) * s + 2.0 * c[2]) * s + c[3]
    return value, slope


@kernel
def _poly3(c, s):
    """Derivative of the quartic c (a cubic) and its own derivative."""
    value = ((4.0 * c[0] * s + 3.0 * c[1]) * s + 2.0 * c[2]) * s + c[3]
    slope = (12.0 * c[0] * s + 6.0 * c[1]) * s + 2.0 * c[2]
    return value, slope


@kernel
def _bracketed_root(c, cubic, lo, hi, f_lo):
    """The root of the quartic c (or of its derivative if cubic) in [lo, hi], where it
    changes sign once; f_lo is its value at lo. Newton steps, bisection when they leave
    the bracket or stall."""
    s = 0.5 * (lo + hi)
    for _ in range(_MAX_ITERATIONS):
        value, slope = _poly3(c, s) if cubic else _poly4(c, s)
        if value == 0.0:
            return s
        if (value < 0.0) == (f_lo < 0.0):
            lo = s
        else:
            hi = s
        step_ok = slope != 0.0
        if step_ok:
            t = s - value / slope
            step_ok = lo < t < hi
        next_s = t if step_ok else 0.5 * (lo + hi)
        if next_s == s or hi - lo <= 4e-16 * max(1.0, abs(s)):
            return next_s
        s = next_s
    return s


@kernel
def _append(found, roots, x):
    """roots (4 floats, the first `found` meaningful) with x added, unless already last."""
    if found > 0 and roots[found - 1] == x or found == 4:
        return found, roots
    r0, r1, r2, r3 = roots
    if found == 0:
        r0 = x
    elif found == 1:
        r1 = x
    elif found == 2:
        r2 = x
    else:
        r3 = x
    return found + 1, (r0, r1, r2, r3)


@kernel
def _sign_change_roots(c, cubic, breaks):
    """Roots of quartic c (or of its derivative if cubic) between consecutive values of the
    sorted 5-tuple `breaks`, one per piece where the sign changes: (found, 4-tuple of roots,
    sorted). Tuples rather than arrays: nothing is allocated per ray."""
    found, roots = 0, (0.0, 0.0, 0.0, 0.0)
    f_lo = (_poly3(c, breaks[0]) if cubic else _poly4(c, breaks[0]))[0]
    for k in range(4):
        lo, hi = breaks[k], breaks[k + 1]
        f_hi = (_poly3(c, hi) if cubic else _poly4(c, hi))[0]
        if f_lo == 0.0:
            found, roots = _append(found, roots, lo)
        elif (f_lo < 0.0) != (f_hi < 0.0) and f_hi != 0.0:
            found, roots = _append(found, roots, _bracketed_root(c, cubic, lo, hi, f_lo))
        f_lo = f_hi
    if f_lo == 0.0:
        found, roots = _append(found, roots, breaks[4])
    return found, roots


@kernel
def _clamp(x, lo, hi):
    return min(max(x, lo), hi)


@kernel
def torus_roots(o, d, major, minor):
    """Sorted t of every crossing of o + t d with the torus, t in any sign:
    (n, t0, t1, t2, t3) with the first n meaningful."""
    length = math.sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2])
    scale = major + minor
    u0, u1, u2 = d[0] / length, d[1] / length, d[2] / length
    # Bounding sphere |p| <= R + r, in the ray's own units (robust discriminant, RTG ch. 7)
    b = o[0] * u0 + o[1] * u1 + o[2] * u2
    f0, f1, f2 = o[0] - b * u0, o[1] - b * u1, o[2] - b * u2
    miss_squared = f0 * f0 + f1 * f1 + f2 * f2
    if miss_squared > scale * scale:
        return 0, 0.0, 0.0, 0.0, 0.0
    half_chord = math.sqrt(scale * scale - miss_squared)
    # Start where the ray enters the sphere: every crossing lies on the chord after it
    t_start = -b - half_chord
    lo_s, hi_s = 0.0, 2.0 * half_chord / scale
    # Normalised frame: lengths in units of R + r, s = (t - t_start) / (R + r)
    p0 = (o[0] + t_start * u0) / scale
    p1 = (o[1] + t_start * u1) / scale
    p2 = (o[2] + t_start * u2) / scale
    big, small = major / scale, minor / scale
    big2 = big * big
    pu = 2.0 * (p0 * u0 + p1 * u1 + p2 * u2)
    pp = p0 * p0 + p1 * p1 + p2 * p2 + big2 - small * small
    exy = u0 * u0 + u1 * u1
    fxy = 2.0 * (p0 * u0 + p1 * u1)
    gxy = p0 * p0 + p1 * p1
    # f(s) = (s^2 + pu s + pp)^2 - 4 R^2 (exy s^2 + fxy s + gxy)
    c = (
        1.0,
        2.0 * pu,
        pu * pu + 2.0 * pp - 4.0 * big2 * exy,
        2.0 * pu * pp - 4.0 * big2 * fxy,
        pp * pp - 4.0 * big2 * gxy,
    )

    # Pieces where f' is monotonic: split at the roots of f'' = 12 s^2 + 6 c1 s + 2 c2,
    # clamped into the chord (a clamped split is an empty piece, harmless)
    cut0 = cut1 = lo_s
    qa, qb, qc = 12.0, 3.0 * c[1], 2.0 * c[2]  # qa s^2 + 2 qb s + qc
    disc = qb * qb - qa * qc
    if disc > 0.0:
        q = -(qb + math.copysign(math.sqrt(disc), qb))
        r_a, r_b = q / qa, (qc / q if q != 0.0 else 0.0)
        cut0, cut1 = _clamp(min(r_a, r_b), lo_s, hi_s), _clamp(max(r_a, r_b), lo_s, hi_s)
    n_slope, slope = _sign_change_roots(c, True, (lo_s, cut0, cut1, hi_s, hi_s))

    # Pieces where f is monotonic: split at the roots of f' (sorted; unused ones at the end)
    cuts = (
        slope[0] if n_slope > 0 else hi_s,
        slope[1] if n_slope > 1 else hi_s,
        slope[2] if n_slope > 2 else hi_s,
    )
    n, roots = _sign_change_roots(c, False, (lo_s, cuts[0], cuts[1], cuts[2], hi_s))
    return (
        n,
        (t_start + roots[0] * scale) / length,
        (t_start + roots[1] * scale) / length,
        (t_start + roots[2] * scale) / length,
        (t_start + roots[3] * scale) / length,
    )
