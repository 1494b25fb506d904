"""Eight-wide mesh BVH: the binary SAH tree collapsed so that each node holds eight children,
tested at once in float32.

A ray tests eight child boxes at a time; the layout lets LLVM's SLP vectorizer turn those
eight slab tests into single 256-bit vector instructions (enabled in `core.jit`). One node is

    boxes[node]  (6, 8) float32: rows lo x, lo y, lo z, hi x, hi y, hi z; one column a child
    links[node]  (8,)   int32:   >= 0 an inner child node; < 0 a leaf, ~(block << 3 | count)
                                 naming the `count` triangles of leaf block `block`
                                 (see `core.kernels.triangles`)

An unused slot has the empty box (lo = +inf, hi = -inf), which every ray misses.

The slab test runs in float32 (`core.kernels.slabs.child_entries`) and stays conservative:
it never culls a box the exact ray meets.

Measured on the million-triangle benchmark mesh (mesh traversal alone, one process, as Mrays/s
per core, primary / incoherent / shadow): four-wide in float64, 6.5 / 1.35 / 3.0; eight-wide
in float32 with the leaf blocks below, 6.6 / 1.5 / 3.5; with prefetching of the children a
closest-hit ray will open, 7.0 / 1.45 / 3.5 (see `core.kernels.prefetch`). Nodes visited per
ray: 7.1 -> 4.8 primary, 13.7 -> 8.8 incoherent.

The binary SAH tree is collapsed into this one by `core.kernels.bvh_collapse`.
"""

import numpy as np

from ..jit.decorators import inlined_kernel

WIDTH = 8
LEAF_COUNT_BITS = 3  # so a leaf holds at most 7 triangles
_LEAF_COUNT_MASK = (1 << LEAF_COUNT_BITS) - 1


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
