"""Watertight ray/triangle intersection (Woop, Benthin and Wald, JCGT 2013).

The ray is sheared so that it runs along +z from the origin; each triangle edge then gets a
2D edge function. An edge shared by two triangles is evaluated from the same two vertices in
the same order by both, with swapped signs, so a ray can never slip between them: the test
is watertight at shared edges and vertices, which ordinary Moller-Trumbore is not. Vertices
are stored in float32 and converted exactly to float64, where all arithmetic happens.

Triangles are read from `corners` (t, 9) float32: x y z of corner 0, then 1, then 2, stored
in BVH leaf order, so a leaf's triangles are one contiguous block and no vertex index is
followed during traversal.
"""

from core.jit import kernel
from core.kernels.shapes import NO_HIT


@kernel
def shear_setup(d):
    """Per-ray constants: the axis permutation (kx, ky, kz) and shear (sx, sy, sz)."""
    ax, ay, az = abs(d[0]), abs(d[1]), abs(d[2])
    kz = 0 if ax >= ay and ax >= az else (1 if ay >= az else 2)
    kx = (kz + 1) % 3
    ky = (kx + 1) % 3
    if d[kz] < 0.0:
        kx, ky = ky, kx  # keep the winding, so that edge signs stay consistent
    sz = 1.0 / d[kz]
    return kx, ky, kz, d[kx] * sz, d[ky] * sz, sz


@kernel
def permuted(o, shear):
    """The ray origin in the shear's axis order: (o[kx], o[ky], o[kz])."""
    return o[shear[0]], o[shear[1]], o[shear[2]]


@kernel
def intersect_triangle(corners, tri, o, shear, t_max):
    """(t, b1, b2) where o + t d meets triangle `tri` of `corners` with 0 < t < t_max, b1
    and b2 the barycentric weights of corners 1 and 2; (NO_HIT, 0, 0) on a miss. `o` is the
    origin from `permuted`, `shear` from `shear_setup`."""
    kx, ky, kz, sx, sy, sz = shear
    ox, oy, oz = o
    a2 = corners[tri, kz] - oz
    b2 = corners[tri, 3 + kz] - oz
    c2 = corners[tri, 6 + kz] - oz
    ax = corners[tri, kx] - ox - sx * a2
    ay = corners[tri, ky] - oy - sy * a2
    bx = corners[tri, 3 + kx] - ox - sx * b2
    by = corners[tri, 3 + ky] - oy - sy * b2
    cx = corners[tri, 6 + kx] - ox - sx * c2
    cy = corners[tri, 6 + ky] - oy - sy * c2
    u = cx * by - cy * bx
    v = ax * cy - ay * cx
    w = bx * ay - by * ax
    if (u < 0.0 or v < 0.0 or w < 0.0) and (u > 0.0 or v > 0.0 or w > 0.0):
        return NO_HIT, 0.0, 0.0
    det = u + v + w
    if det == 0.0:
        return NO_HIT, 0.0, 0.0
    t = (u * a2 + v * b2 + w * c2) * sz / det
    if not 0.0 < t < t_max:
        return NO_HIT, 0.0, 0.0
    return t, v / det, w / det
