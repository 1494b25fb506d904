"""The binary SAH tree of a mesh collapsed into the eight-wide tree that traversal walks
(layout in `core.kernels.bvh_wide`), at the least expected cost.

A wide node is made of some binary node; its children are binary nodes below it, at most
WIDTH of them, each a binary leaf or the root of another wide node. Which binary nodes become
wide nodes is the only choice: every binary leaf stays a leaf block, tested whenever a ray
enters its box, whatever wide node holds it. So the expected cost of a collapse is the cost of
its node visits: a ray that reaches the root enters a node's box with a chance proportional
to its surface area, and a visit costs one eight-wide slab test however many slots are
filled. The collapse minimises the summed surface area of its wide nodes, exactly, by dynamic
programming over the binary tree (as Ylitie, Karras and Laine 2017 do for their compressed
wide BVHs, without their merging of leaves: ours are fixed blocks of four).

For each binary node m and j = 1..WIDTH, forest[m, j] is the least cost of covering m's
subtree with at most j wide children: m itself as one child (a leaf costs nothing, an inner
node its area plus the cost of its own best forest of WIDTH), or the best split of j between
its two children. The greedy collapse this replaced (open the child of largest area until
eight are held) left 4.4 of 8 slots filled on the million-triangle benchmark mesh; this
fills 6.1, with 58 000 nodes instead of 87 000, and traces 5-7% more rays per second.
"""

import numpy as np

from ..jit.decorators import allocating_kernel, kernel
from .bvh_wide import LEAF_COUNT_BITS, WIDTH

# How a binary node m covers its subtree with at most j children, choice[m, j]:
_AS_ONE_CHILD = 0  # m is a single child (a leaf, or the root of a wide node)
_WITH_FEWER = -1  # as with at most j - 1
# > 0: its left child covers its own subtree with at most choice[m, j], the right with the rest


@kernel
def _half_area(lo, hi, m):
    dx, dy, dz = hi[m, 0] - lo[m, 0], hi[m, 1] - lo[m, 1], hi[m, 2] - lo[m, 2]
    return dx * dy + dy * dz + dz * dx


@allocating_kernel
def collapse_choices(lo, hi, info):
    """choice (n, WIDTH + 1) int8 as above, and split (n,) int8: how an inner node that is a
    wide node shares its WIDTH slots between its two children. Children come after their
    parent in `build_bvh`'s numbering, so one backward pass sees them first."""
    n = info.shape[0]
    forest = np.zeros((n, WIDTH + 1))
    choice = np.zeros((n, WIDTH + 1), np.int8)
    split = np.zeros(n, np.int8)
    for m in range(n - 1, -1, -1):
        if info[m, 1] > 0:
            continue  # a leaf: forest[m, :] = 0, as one child
        left, right = info[m, 0], info[m, 0] + 1
        for j in range(2, WIDTH + 1):
            best, best_k = np.inf, 1
            for k in range(1, j):
                cost = forest[left, k] + forest[right, j - k]
                if cost < best:
                    best, best_k = cost, k
            forest[m, j], choice[m, j] = best, best_k
        split[m] = choice[m, WIDTH]
        as_one = _half_area(lo, hi, m) + forest[m, WIDTH]
        forest[m, 1], choice[m, 1] = as_one, _AS_ONE_CHILD
        for j in range(2, WIDTH + 1):
            if as_one <= forest[m, j]:
                forest[m, j], choice[m, j] = as_one, _AS_ONE_CHILD
            if forest[m, j - 1] < forest[m, j]:
                forest[m, j], choice[m, j] = forest[m, j - 1], _WITH_FEWER
    return choice, split


@kernel
def _children_of(node, info, choice, split, children, pending_node, pending_j):
    """The binary nodes that are the wide children of binary node `node`, into children;
    returns their count."""
    if info[node, 1] > 0:
        children[0] = node  # a tree that is one leaf
        return 1
    left = info[node, 0]
    pending_node[0], pending_j[0] = left + 1, WIDTH - split[node]
    pending_node[1], pending_j[1] = left, split[node]
    waiting, filled = 2, 0
    while waiting > 0:
        waiting -= 1
        m, j = pending_node[waiting], pending_j[waiting]
        how = choice[m, j]
        if how == _WITH_FEWER:
            pending_j[waiting] = j - 1
            waiting += 1
        elif how == _AS_ONE_CHILD:
            children[filled] = m
            filled += 1
        else:
            pending_node[waiting], pending_j[waiting] = info[m, 0] + 1, j - how
            pending_node[waiting + 1], pending_j[waiting + 1] = info[m, 0], how
            waiting += 2
    return filled


@allocating_kernel
def collapse_to_wide(lo, hi, info):
    """The eight-wide tree of the binary tree (lo, hi (n, 3) float32 boxes, info (n, 2) from
    `build_bvh`). Returns (boxes, links) with node 0 the root and nodes numbered breadth
    first; links are local to this tree, leaves ~(first << 3 | count) over leaf-ordered
    triangles. A tree over no triangles becomes one node whose slots are all empty."""
    binary_count = info.shape[0]
    boxes = np.empty((binary_count, 6, WIDTH), np.float32)
    boxes[:, :3, :] = np.inf
    boxes[:, 3:, :] = -np.inf
    links = np.full((binary_count, WIDTH), -1, np.int32)
    # Breadth first: queue[w] is the binary node that wide node w is made of
    queue = np.empty(binary_count, np.int64)
    queue[0] = 0
    head, tail = 0, 1
    if binary_count == 1 and info[0, 1] == 0:
        return boxes, links  # no triangles: one node with every slot empty
    choice, split = collapse_choices(lo, hi, info)
    children = np.empty(WIDTH, np.int64)
    # Each step replaces one pending entry by at most two, and at most WIDTH are ever held
    pending_node = np.empty(WIDTH + 2, np.int64)
    pending_j = np.empty(WIDTH + 2, np.int64)
    while head < tail:
        wide, node = head, queue[head]
        head += 1
        filled = _children_of(node, info, choice, split, children, pending_node, pending_j)
        for c in range(filled):
            child = children[c]
            for a in range(3):
                boxes[wide, a, c] = lo[child, a]
                boxes[wide, 3 + a, c] = hi[child, a]
            count = info[child, 1]
            if count > 0:
                links[wide, c] = ~((info[child, 0] << LEAF_COUNT_BITS) | count)
            else:
                links[wide, c] = tail
                queue[tail] = child
                tail += 1
    return boxes[:tail].copy(), links[:tail].copy()
