"""Eight-wide mesh BVH: the binary SAH tree collapsed so that each node holds eight children,
tested at once in float32.

A ray tests eight child boxes at a time; the layout lets LLVM's SLP vectorizer turn those
eight slab tests into single 256-bit vector instructions (enabled in `core.jit`). One node is

    boxes[node]  (6, 8) float32: rows lo x, lo y, lo z, hi x, hi y, hi z; one column a child
    links[node]  (8,)   int32:   >= 0 an inner child node; < 0 a leaf, ~(block << 3 | count)
                                 naming the `count` triangles of leaf block `block`
                                 (see `core.kernels.triangles`)

An unused slot has the empty box (lo = +inf, hi = -inf), which every ray misses.

The slab test runs in float32 and stays conservative (it never culls a box the exact ray
meets): the ray origin is rounded per axis towards the side that can only lower a near
distance and raise a far one (`SlabRay`), and the far distance is widened by more than its
float32 roundings can move it: those of (box - origin) * inverse, of the inverse itself and of
the widening product (`SLAB_WIDEN32`; Ize 2013, in float32).

Measured on the million-triangle benchmark mesh (mesh traversal alone, one process, as Mrays/s
per core, primary / incoherent / shadow): four-wide in float64, 6.5 / 1.35 / 3.0; eight-wide
in float32 with the leaf blocks below, 6.6 / 1.5 / 3.5; with prefetching of the children a
closest-hit ray will open, 7.0 / 1.45 / 3.5 (see `core.kernels.prefetch`). Nodes visited per
ray: 7.1 -> 4.8 primary, 13.7 -> 8.8 incoherent.

The binary SAH tree is collapsed into this one by `core.kernels.bvh_collapse`.
"""

from typing import NamedTuple

import numpy as np

from ..jit import inlined_kernel, ir_inlined_kernel
from .vec import inverse

WIDTH = 8
LEAF_COUNT_BITS = 3  # so a leaf holds at most 7 triangles
_LEAF_COUNT_MASK = (1 << LEAF_COUNT_BITS) - 1
# A box's far distance is widened by 2 gamma_3 (Ize 2013), so that rounding in the slab test
# never culls a box the ray truly crosses: in float64 for the top level's boxes ...
SLAB_WIDEN = 1.0 + 6.0 * 2.0**-53
# ... and in float32 for the mesh nodes, where the inverse direction adds a fourth rounding
# (float64 1/d to float32) and the widening product a fifth: 10 units of 2^-24 cover them
SLAB_WIDEN32 = np.float32(1.0 + 5.0 * 2.0**-23)
INF32 = np.float32(np.inf)
_ULP32 = np.float32(2.0**-23)  # at least one float32 step of any normal float32 |y|
_MIN32 = np.float32(np.finfo(np.float32).tiny)
_MAX32 = float(np.finfo(np.float32).max)
_MAX32_F = np.float32(_MAX32)


def number_leaf_blocks(links: np.ndarray):
    """Leaves renamed from ranges of leaf-ordered triangles to blocks of four triangles (one
    block a leaf, numbered as the leaves appear, so that siblings' blocks lie side by side).
    Returns (links, first, count): leaf links ~(block << 3 | count), and each block's first
    leaf-ordered triangle and its count."""
    links = links.astype(np.int64)
    leaf = (links < 0) & (links != -1)
    code = ~links[leaf]
    blocks = len(code)
    links[leaf] = ~((np.arange(blocks) << LEAF_COUNT_BITS) | (code & _LEAF_COUNT_MASK))
    return links.astype(np.int32), code >> LEAF_COUNT_BITS, code & _LEAF_COUNT_MASK


def offset_links(links: np.ndarray, base_node: int, base_block: int) -> np.ndarray:
    """Links of one mesh's tree made global: inner nodes shifted by base_node, leaf blocks
    by base_block (unused slots stay -1)."""
    links = links.astype(np.int64)
    leaf = links < 0
    code = ~links[leaf]
    block = (code >> LEAF_COUNT_BITS) + base_block
    shifted = np.where(code == 0, code, (block << LEAF_COUNT_BITS) | (code & _LEAF_COUNT_MASK))
    links[leaf] = ~shifted
    links[~leaf] += base_node
    return links.astype(np.int32)


@inlined_kernel
def leaf_range(link):
    """(first, end) of what leaf link `link` (< 0) names: leaf-ordered triangles as
    `collapse_to_wide` returns them, blocks after `number_leaf_blocks` (end = first + count)."""
    code = ~link
    first = code >> LEAF_COUNT_BITS
    return first, first + (code & _LEAF_COUNT_MASK)


@inlined_kernel
def leaf_block(link):
    """The triangle block of leaf link `link` (< 0) in a packed tree."""
    return (~link) >> LEAF_COUNT_BITS


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


class SlabRay(NamedTuple):
    """What the float32 slab test needs of a ray, worked out once per ray: the inverse
    direction for near planes and for far planes, the origin rounded for near planes and for
    far planes, and the box rows the ray enters and leaves by."""

    near_inverse: tuple  # float32 (3,): 1 / d, held finite
    far_inverse: tuple  # float32 (3,): 1 / d, inf where it leaves float32's range
    near_origin: tuple  # float32 (3,): rounded so that (plane - origin) * inverse can only drop
    far_origin: tuple  # float32 (3,): rounded so that it can only grow
    rows: tuple  # int (6,): from near_far_rows


@inlined_kernel
def slab_ray(o, d):
    """The `SlabRay` of o + t d (float64)."""
    ix, iy, iz = inverse(d)
    # A direction component below 1 / float32's range has an inverse beyond it: held finite
    # for near planes, the entry distances only drop; left to overflow for far planes, the
    # exit distances only grow (to inf, where the exact one is finite but huge)
    near_inverse = (_finite32(ix), _finite32(iy), _finite32(iz))
    far_inverse = (np.float32(ix), np.float32(iy), np.float32(iz))
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
    # An entry beyond float32's range (a huge object-space distance) overflows to inf, which
    # is also the mark of a miss: it enters at the largest float32 instead. (Selects, not
    # branches: a branch here stops the vectorizer, measured 1.4x slower.)
    entry = near if near < _MAX32_F else _MAX32_F
    return entry if near <= far * SLAB_WIDEN32 else INF32


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
