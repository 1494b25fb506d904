"""Adaptive anti-aliasing: a pixel's n x n camera rays only where its samples disagree.

As POV-Ray's adaptive method 1 (and Whitted's 1980 paper) spend camera rays, with one ray
more: every pixel corner of the image gets one ray, shared by the four pixels that meet
there, and every pixel one through its centre. Where a pixel's four corners and centre
agree within the threshold, the pixel weighs them as the quincunx pattern does, half the
centre and an eighth each corner (render_tile divides their sums by 8); where they do not,
it gets its n x n rays, exactly as without adaptive sampling (the same rays, the same
random numbers, the same bits). Agreement is measured on each of R, G, B after
x / (1 + x), which keeps a difference in bright light from counting for more than the eye
sees in it, and on alpha: the largest difference between two of the five, compared with
the threshold.

Why the centre: with corners alone, detail finer than a pixel that the corners happen to
miss (a checkered floor near the pixel pitch, seen directly or through glass) left four
agreeing corners and a wrong pixel, and adaptive sampling lost to the fixed 3 x 3 grid at
equal rays on four sample scenes (refraction by 1.6x); the centre sees between them.

A decision depends only on the pixel's own corners, whose rays depend only on their place
in the image and the seed (their lens point at random over the whole lens), so any
tiling, border or farm split gives the same picture. A tile keeps two rows of corners, the
top and bottom edges of the pixel row (Workspace.corners: each corner's colour, alpha and,
for the passes, its camera ray's record); a pixel traces its bottom-right corner, and the
others no pixel before it in the tile has: one ray a pixel besides the refined pixels'.
What neither the corners nor the centre see -- detail smaller than a pixel that touches
none of the five, a thin line between them -- is missed, as in any such method.
"""

from ..jit.decorators import inlined_kernel
from .pass_record import REC_COUNT, accumulate
from .workspace import CORNER_ALPHA, CORNER_RECORD

# The sample number of a corner's key: past any pixel's n x n (n <= 1024), so that a
# corner's random numbers are its own
CORNER_SAMPLE = 1 << 21
CENTRE_SAMPLE = CORNER_SAMPLE + 1  # a pixel centre's: its own numbers again
TOP, BOTTOM = 0, 1  # Workspace.corners' rows


@inlined_kernel
def corners_to_trace(i, j):
    """How many corners pixel (i, j) of the tile traces: its bottom-right, its bottom-left
    in the tile's first column, its top edge's in the first row."""
    return (2 if i == 0 else 1) * (2 if j == 0 else 1)


@inlined_kernel
def corner_of(k, i, j):
    """(x, y) in the tile, column and row of Workspace.corners of corner k of those pixel
    (i, j) traces: the bottom-right first, then the bottom-left (first column), then the top
    edge's right and left (first row)."""
    left = i == 0
    if k == 0:
        return i + 1, j + 1, i + 1, BOTTOM
    if left and k == 1:
        return i, j + 1, i, BOTTOM
    top = k - (2 if left else 1)  # 0: the top-right, 1: the top-left
    return i + 1 - top, j, i + 1 - top, TOP


@inlined_kernel
def keep_corner(corners, row, column, colour, alpha, record, passes):
    slot = corners[row, column]
    slot[0], slot[1], slot[2], slot[CORNER_ALPHA] = colour[0], colour[1], colour[2], alpha
    if passes:
        for k in range(REC_COUNT):
            slot[CORNER_RECORD + k] = record[k]


@inlined_kernel
def next_corner_row(corners):
    """The bottom edge of the pixel row just done becomes the top edge of the next. Copied
    element by element: a slice assignment compiles numba's shape-mismatch error, whose
    message formatting (strings from integers) took 1.2 s of a cold compile."""
    for i in range(corners.shape[1]):
        for k in range(corners.shape[2]):
            corners[TOP, i, k] = corners[BOTTOM, i, k]


@inlined_kernel
def samples_differ(corners, i, centre, threshold):
    """True where the colours (compressed by x / (1 + x)) or alphas of pixel i's four
    corners and its centre (r, g, b, alpha) differ by more than the threshold."""
    for k in range(4):
        lo = hi = centre[k]
        for row, column in ((TOP, i), (TOP, i + 1), (BOTTOM, i), (BOTTOM, i + 1)):
            value = corners[row, column, k]
            lo, hi = min(lo, value), max(hi, value)
        if k < CORNER_ALPHA:
            lo, hi = lo / (1.0 + abs(lo)), hi / (1.0 + abs(hi))
        if hi - lo > threshold:
            return True
    return False


@inlined_kernel
def corner_mean(corners, i, ws, passes, frame, axis):
    """The sums of pixel i's four corners' colours and alphas (and their records folded into
    the pixel's passes)."""
    r = g = b = a = 0.0
    for s in range(4):
        slot = corners[TOP + s // 2, i + s % 2]
        r += slot[0]
        g += slot[1]
        b += slot[2]
        a += slot[CORNER_ALPHA]
        if passes:
            for k in range(ws.record.shape[0]):  # no slice copy: it compiles an allocation
                ws.record[k] = slot[CORNER_RECORD + k]
            accumulate(ws.accum, ws.crypto_ids, ws.record, s, frame, axis)
    return r, g, b, a
