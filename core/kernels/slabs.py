"""The two slab tests (Kay and Kajiya 1986): a box against a ray segment or a whole line.

- `box_entry`, in float64, for the world-space boxes of shapes: the top-level BVH's nodes
  (`core.kernels.trace`), an area light's candidates, and a CSG operand's box along the
  whole line (`core.kernels.csg`, t from -inf to inf).
- `child_entries`, in float32, for the eight children of a mesh BVH node at once
  (`core.kernels.bvh_wide`), and `slab_ray`, what it needs of a ray, worked out once.

Both are conservative: they never cull a box the exact ray or line meets. Rounding can only
move a computed distance by a few units of its own magnitude, so the exit distance is widened
by that much, `widened` and `widened32`: by |t| times the slack, which is a widening at
either sign (a line's exit distance behind its origin is negative, where multiplying by
1 + slack would narrow it). A NaN (a ray in a box's face plane, 0 * inf) fails every
comparison and so never culls either.
"""

import math
from typing import NamedTuple

import numpy as np

from ..jit.decorators import inlined_kernel, ir_inlined_kernel
from .shapes import NO_HIT
from .vec import inverse

# 2 gamma_3 (Ize 2013): the three roundings of (plane - origin) * inverse, in float64 ...
SLAB_SLACK = 6.0 * 2.0**-53
# ... and in float32, where the inverse direction adds a fourth rounding (float64 1 / d to
# float32) and the widening a fifth: 10 units of 2^-24 cover them
SLAB_SLACK32 = np.float32(5.0 * 2.0**-23)
INF32 = np.float32(np.inf)
_ULP32 = np.float32(2.0**-23)  # at least one float32 step of any normal float32 |y|
_MIN32 = np.float32(np.finfo(np.float32).tiny)
_MAX32 = float(np.finfo(np.float32).max)
_MAX32_F = np.float32(_MAX32)
_LOWEST32 = np.float32(-_MAX32)
_NAN32 = np.float32(np.nan)


@inlined_kernel
def widened(t):
    """t moved away from the box by more than the float64 slab test's rounding."""
    return t + abs(t) * SLAB_SLACK


@inlined_kernel
def widened32(t):
    """`widened` for the float32 slab test."""
    return t + abs(t) * SLAB_SLACK32


@inlined_kernel
def _slab(lo, hi, o, i, t_near, t_far):
    """One axis of `box_entry`: the slab's entry and exit, ordered, clip [t_near, t_far].
    Selects rather than a swap, so that rays of random direction do not mispredict a branch
    per axis; the same comparisons, so the same bits."""
    t0 = (lo - o) * i
    t1 = (hi - o) * i
    swap = t0 > t1
    enter = t1 if swap else t0
    leave = t0 if swap else t1
    t_near = enter if enter > t_near else t_near
    t_far = leave if leave < t_far else t_far
    return t_near, t_far


@inlined_kernel
def box_entry(bounds, k, o, inverse_d, t_min, t_max):
    """Where o + t d enters box k of bounds (n, 6+) = (lo xyz, hi xyz, ...) within
    [t_min, t_max] (inverse_d = 1 / d per component): the entry distance, t_min if o is
    inside, NO_HIT if it misses. For a whole line, t_min = -inf and t_max = inf."""
    t_near, t_far = _slab(bounds[k, 0], bounds[k, 3], o[0], inverse_d[0], t_min, t_max)
    t_near, t_far = _slab(bounds[k, 1], bounds[k, 4], o[1], inverse_d[1], t_near, t_far)
    t_near, t_far = _slab(bounds[k, 2], bounds[k, 5], o[2], inverse_d[2], t_near, t_far)
    return t_near if t_near <= widened(t_far) else NO_HIT


@inlined_kernel
def near_far_rows(ix, iy, iz):
    """Rows of a node's boxes that the ray (inverse direction i) enters and leaves by on
    each axis: with a positive component it enters by lo, else by hi."""
    nx = 0 if ix >= 0.0 else 3
    ny = 1 if iy >= 0.0 else 4
    nz = 2 if iz >= 0.0 else 5
    return nx, ny, nz, 3 - nx, 5 - ny, 7 - nz


@inlined_kernel
def _finite32(x):
    """x rounded to float32, held within its finite range."""
    return np.float32(min(max(x, -_MAX32), _MAX32))


@inlined_kernel
def float32_below(x):
    """A float32 no greater than the float64 x (-inf below float32's range). A select, not
    a branch: for rays of random origin the branch mispredicted half the time (the ray setup
    of `core.kernels.mesh_trace` took 28 ns, 14 ns as selects, the same bits)."""
    y = _finite32(x)
    lower = y - abs(y) * _ULP32 - _MIN32
    return lower if y > x else y


@inlined_kernel
def float32_above(x):
    """A float32 no smaller than the float64 x (+inf above float32's range)."""
    y = _finite32(x)
    upper = y + abs(y) * _ULP32 + _MIN32
    return upper if y < x else y


@inlined_kernel
def _axis_inverses32(i, whole_line):
    """One axis's (near, far) float32 inverse directions, from the float64 inverse i.

    A direction component below 1 / float32's range has an inverse beyond it. For a ray it is
    held finite for near planes, so the entry distances only drop, and left to overflow for
    far planes, so the exit distances only grow (to inf, where the exact one is finite but
    huge). Both rules assume distances of one sign: along a whole line an entry behind the
    origin would rise and an exit fall, so there the axis is left out (NaN, which never
    culls). A component of 0 keeps its infinite inverse, exact on both sides: a line in a
    near plane then gets NaN there and the plane is skipped (held finite, it gave an entry of
    0, which culled the box of a line lying behind its origin: found by the whole-line test).
    Branches, not selects: once per ray, and almost never taken."""
    far = np.float32(i)
    if math.isinf(i):
        return far, far
    if whole_line and math.isinf(far):
        return _NAN32, _NAN32
    return _finite32(i), far


class SlabRay(NamedTuple):
    """What the float32 slab test needs of a ray, worked out once per ray: the inverse
    direction for near planes and for far planes, the origin rounded for near planes and for
    far planes, and the box rows the ray enters and leaves by."""

    near_inverse: tuple  # float32 (3,): 1 / d, held finite (see _axis_inverses32)
    far_inverse: tuple  # float32 (3,): 1 / d, inf where it leaves float32's range
    near_origin: tuple  # float32 (3,): rounded so that (plane - origin) * inverse can only drop
    far_origin: tuple  # float32 (3,): rounded so that it can only grow
    rows: tuple  # int (6,): from near_far_rows


@inlined_kernel
def slab_ray(o, d, whole_line):
    """The `SlabRay` of o + t d (float64), for t >= 0 or, if whole_line, for every t."""
    ix, iy, iz = inverse(d)
    nix, fix = _axis_inverses32(ix, whole_line)
    niy, fiy = _axis_inverses32(iy, whole_line)
    niz, fiz = _axis_inverses32(iz, whole_line)
    near_inverse, far_inverse = (nix, niy, niz), (fix, fiy, fiz)
    # Entering by lo with a positive inverse, t = (lo - o) * i drops as o grows; entering by
    # hi with a negative one, it drops as o shrinks. The far planes go the other way.
    below = (float32_below(o[0]), float32_below(o[1]), float32_below(o[2]))
    above = (float32_above(o[0]), float32_above(o[1]), float32_above(o[2]))
    near_origin = (
        above[0] if ix >= 0.0 else below[0],
        above[1] if iy >= 0.0 else below[1],
        above[2] if iz >= 0.0 else below[2],
    )
    far_origin = (
        below[0] if ix >= 0.0 else above[0],
        below[1] if iy >= 0.0 else above[1],
        below[2] if iz >= 0.0 else above[2],
    )
    return SlabRay(near_inverse, far_inverse, near_origin, far_origin, near_far_rows(ix, iy, iz))


@inlined_kernel
def _slab_entry(b, c, ray, t_min, t_max):
    nx, ny, nz, fx, fy, fz = ray.rows
    nix, niy, niz = ray.near_inverse
    fix, fiy, fiz = ray.far_inverse
    (nox, noy, noz), (fox, foy, foz) = ray.near_origin, ray.far_origin
    t0 = (b[nx, c] - nox) * nix
    t1 = (b[fx, c] - fox) * fix
    t2 = (b[ny, c] - noy) * niy
    t3 = (b[fy, c] - foy) * fiy
    t4 = (b[nz, c] - noz) * niz
    t5 = (b[fz, c] - foz) * fiz
    # Written as comparisons so that a NaN (the ray in a face's plane) is skipped and never
    # culls, and so that LLVM maps them onto vector max/min
    near = t_min
    near = t0 if t0 > near else near
    near = t2 if t2 > near else near
    near = t4 if t4 > near else near
    far = t_max
    far = t1 if t1 < far else far
    far = t3 if t3 < far else far
    far = t5 if t5 < far else far
    # An exit far behind a line's origin, beyond float32's range, overflows to -inf, where the
    # exact one is finite: held at the lowest float32, so it can only grow (for a ray, any
    # exit below 0 is a miss either way)
    far = far if far > _LOWEST32 else _LOWEST32
    # An entry beyond float32's range (a huge object-space distance) overflows to inf, which
    # is also the mark of a miss: it enters at the largest float32 instead. (Selects, not
    # branches: a branch here stops the vectorizer, measured 1.4x slower.)
    entry = near if near < _MAX32_F else _MAX32_F
    return entry if near <= widened32(far) else INF32


@ir_inlined_kernel
def child_entries(boxes, node, ray, t_min, t_max):
    """Entry distances (float32) of the ray into the eight children of `node` within
    [t_min, t_max] (float32, t_max rounded up); INF32 for a child it misses. Eight
    straight-line copies, which the SLP vectorizer merges. Inlined by numba (its eight
    calls, not their bodies), so that the copies are optimized together with the pushes of
    their results in the traversal: 4-5% more mesh shadow rays than as a function LLVM
    optimized alone first (in-process A/B and bench_bvh), and a cold compile no longer."""
    b = boxes[node]
    return (
        _slab_entry(b, 0, ray, t_min, t_max),
        _slab_entry(b, 1, ray, t_min, t_max),
        _slab_entry(b, 2, ray, t_min, t_max),
        _slab_entry(b, 3, ray, t_min, t_max),
        _slab_entry(b, 4, ray, t_min, t_max),
        _slab_entry(b, 5, ray, t_min, t_max),
        _slab_entry(b, 6, ray, t_min, t_max),
        _slab_entry(b, 7, ray, t_min, t_max),
    )
