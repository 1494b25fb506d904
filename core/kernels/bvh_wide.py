"""Four-wide mesh BVH: the binary SAH tree collapsed so that each node holds four children.

A ray then tests four child boxes at a time, and the layout lets LLVM's SLP vectorizer turn
those four slab tests into vector instructions (enabled in `core.jit`): one node is

    boxes[node]  (6, 4) float32: rows lo x, lo y, lo z, hi x, hi y, hi z; one column a child
    links[node]  (4,)   int32:   >= 0 an inner child node; < 0 a leaf, ~(first << 3 | count)
                                 naming triangles first .. first + count - 1

An unused slot has the empty box (lo = +inf, hi = -inf), which every ray misses. Measured on
the million-triangle benchmark mesh, in one process: the binary tree traced 2.7 M primary and
0.56 M incoherent rays/s per core; this one, vectorized, 5.0 and 0.97 (unvectorized 3.1 and
0.73); eight-wide ran no faster than four and took more memory.

Collapsing (as in Wald et al. 2008, "Getting rid of packets"): a wide node starts with the two
children of a binary node and keeps opening its inner child of largest surface area until
it holds four children or only leaves.
"""

import numpy as np

from core.jit import inlined_kernel, kernel

WIDTH = 4
LEAF_COUNT_BITS = 3  # so a leaf holds at most 7 triangles
_LEAF_COUNT_MASK = (1 << LEAF_COUNT_BITS) - 1
# A box's far distance is widened by 2 gamma_3 (Ize 2013), so that rounding in the slab test
# never culls a box the ray truly crosses
SLAB_WIDEN = 1.0 + 6.0 * 2.0**-53


@kernel
def _half_area(lo, hi, k):
    dx, dy, dz = hi[k, 0] - lo[k, 0], hi[k, 1] - lo[k, 1], hi[k, 2] - lo[k, 2]
    return dx * dy + dy * dz + dz * dx


@kernel
def collapse_to_wide(lo, hi, info):
    """The four-wide tree of the binary tree (lo, hi (n, 3) float32 boxes, info (n, 2) from
    `build_bvh`). Returns (boxes, links) with node 0 the root; links are local to this tree.
    A tree over no triangles becomes one node whose slots are all empty."""
    binary_count = info.shape[0]
    boxes = np.empty((binary_count, 6, WIDTH), np.float32)
    boxes[:, :3, :] = np.inf
    boxes[:, 3:, :] = -np.inf
    links = np.full((binary_count, WIDTH), -1, np.int32)
    # Breadth-first over wide nodes: queue holds (binary node, its wide node)
    queue_binary = np.empty(binary_count, np.int64)
    queue_wide = np.empty(binary_count, np.int64)
    queue_binary[0], queue_wide[0] = 0, 0
    head, tail, wide_count = 0, 1, 1
    if binary_count == 1 and info[0, 1] == 0:
        tail = 0  # no triangles: one node with every slot empty
    children = np.empty(WIDTH, np.int64)
    while head < tail:
        node, wide = queue_binary[head], queue_wide[head]
        head += 1
        if info[node, 1] > 0:  # a binary tree that is one leaf
            children[0] = node
            filled = 1
        else:
            children[0], children[1] = info[node, 0], info[node, 0] + 1
            filled = 2
            while filled < WIDTH:
                largest, largest_area = -1, -1.0
                for c in range(filled):
                    if info[children[c], 1] == 0:
                        area = _half_area(lo, hi, children[c])
                        if area > largest_area:
                            largest, largest_area = c, area
                if largest < 0:
                    break
                opened = children[largest]
                children[largest] = info[opened, 0]
                children[filled] = info[opened, 0] + 1
                filled += 1
        for c in range(filled):
            child = children[c]
            for a in range(3):
                boxes[wide, a, c] = lo[child, a]
                boxes[wide, 3 + a, c] = hi[child, a]
            count = info[child, 1]
            if count > 0:
                links[wide, c] = ~((info[child, 0] << LEAF_COUNT_BITS) | count)
            else:
                links[wide, c] = wide_count
                queue_binary[tail], queue_wide[tail] = child, wide_count
                tail += 1
                wide_count += 1
    return boxes[:wide_count].copy(), links[:wide_count].copy()


def offset_links(links: np.ndarray, base_node: int, base_triangle: int) -> np.ndarray:
    """Links of one mesh's tree made global: inner nodes shifted by base_node, leaf
    triangles by base_triangle (unused slots stay -1)."""
    links = links.astype(np.int64)
    leaf = links < 0
    code = ~links[leaf]
    first = (code >> LEAF_COUNT_BITS) + base_triangle
    shifted = np.where(code == 0, code, (first << LEAF_COUNT_BITS) | (code & _LEAF_COUNT_MASK))
    links[leaf] = ~shifted
    links[~leaf] += base_node
    return links.astype(np.int32)


@inlined_kernel
def leaf_range(link):
    """(first, end) of the triangles of leaf link `link` (< 0)."""
    code = ~link
    first = code >> LEAF_COUNT_BITS
    return first, first + (code & _LEAF_COUNT_MASK)


@inlined_kernel
def near_far_rows(ix, iy, iz):
    """Rows of a node's boxes that the ray (inverse direction i) enters and leaves by on
    each axis: with a positive component it enters by lo, else by hi."""
    nx = 0 if ix >= 0.0 else 3
    ny = 1 if iy >= 0.0 else 4
    nz = 2 if iz >= 0.0 else 5
    return nx, ny, nz, 3 - nx, 5 - ny, 7 - nz


@inlined_kernel
def _slab_entry(b, c, rows, ox, oy, oz, ix, iy, iz, t_min, t_max):
    nx, ny, nz, fx, fy, fz = rows
    t0 = (b[nx, c] - ox) * ix
    t1 = (b[fx, c] - ox) * ix
    t2 = (b[ny, c] - oy) * iy
    t3 = (b[fy, c] - oy) * iy
    t4 = (b[nz, c] - oz) * iz
    t5 = (b[fz, c] - oz) * iz
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
    return near if near <= far * SLAB_WIDEN else np.inf


@inlined_kernel
def child_entries(boxes, node, rows, ox, oy, oz, ix, iy, iz, t_min, t_max):
    """Entry distances of the ray into the four children of `node` within [t_min, t_max];
    inf for a child it misses. Four straight-line copies, which the SLP vectorizer merges."""
    b = boxes[node]
    return (
        _slab_entry(b, 0, rows, ox, oy, oz, ix, iy, iz, t_min, t_max),
        _slab_entry(b, 1, rows, ox, oy, oz, ix, iy, iz, t_min, t_max),
        _slab_entry(b, 2, rows, ox, oy, oz, ix, iy, iz, t_min, t_max),
        _slab_entry(b, 3, rows, ox, oy, oz, ix, iy, iz, t_min, t_max),
    )
