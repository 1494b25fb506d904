"""Watertight ray/triangle intersection (Woop, Benthin and Wald, JCGT 2013).

The ray is sheared so that it runs along +z from the origin; each triangle edge then gets a
2D edge function. An edge shared by two triangles is evaluated from the same two vertices in
the same order by both, with swapped signs, so a ray can never slip between them: the test
is watertight at shared edges and vertices, which ordinary Moller-Trumbore is not. Vertices
are stored in float32 and converted exactly to float64, where all arithmetic happens.
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
def intersect_triangle(vertices, i0, i1, i2, o, shear, t_max):
    """(t, b1, b2) where o + t d meets triangle (i0, i1, i2) with 0 < t < t_max, b1 and b2
    the barycentric weights of vertices i1 and i2; (NO_HIT, 0, 0) on a miss."""
    kx, ky, kz, sx, sy, sz = shear
    a0 = vertices[i0, kx] - o[kx]
    a1 = vertices[i0, ky] - o[ky]
    a2 = vertices[i0, kz] - o[kz]
    b0 = vertices[i1, kx] - o[kx]
    b1 = vertices[i1, ky] - o[ky]
    b2 = vertices[i1, kz] - o[kz]
    c0 = vertices[i2, kx] - o[kx]
    c1 = vertices[i2, ky] - o[ky]
    c2 = vertices[i2, kz] - o[kz]
    ax, ay = a0 - sx * a2, a1 - sy * a2
    bx, by = b0 - sx * b2, b1 - sy * b2
    cx, cy = c0 - sx * c2, c1 - sy * c2
    u = cx * by - cy * bx
    v = ax * cy - ay * cx
    w = bx * ay - by * ax
    if (u < 0.0 or v < 0.0 or w < 0.0) and (u > 0.0 or v > 0.0 or w > 0.0):
        return NO_HIT, 0.0, 0.0
    det = u + v + w
    if det == 0.0:
        return NO_HIT, 0.0, 0.0
    t = (u * (sz * a2) + v * (sz * b2) + w * (sz * c2)) / det
    if not 0.0 < t < t_max:
        return NO_HIT, 0.0, 0.0
    return t, v / det, w / det
