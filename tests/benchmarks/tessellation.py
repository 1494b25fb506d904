"""The core's canonical shapes as smooth-shaded triangle meshes of a chosen size, the way a
modeller would build them: parametric grids with roughly square cells, the exact normal at
every triangle corner, flat caps. Written for the analytic-against-tessellated benchmark.

Every patch evaluates its points from the same angles, so edges that two patches share (a
cylinder's rim) get bit-identical vertices and the mesh has no cracks.
"""

import math

import numpy as np

from core import TriangleMesh

TORUS_MAJOR, TORUS_MINOR = 1.0, 0.4


def _grid(point_normal, nu, nv, smooth):
    """Triangles of an nu x nv grid over (u, v) in [0, 1]^2: corners (t, 3, 3), corner
    normals (t, 3, 3), per-face smooth flags; triangles collapsed at a pole are dropped."""
    u, v = np.meshgrid(np.arange(nu + 1) / nu, np.arange(nv + 1) / nv, indexing="ij")
    p, n = point_normal(u, v)  # (nu + 1, nv + 1, 3) each
    i, j = np.meshgrid(np.arange(nu), np.arange(nv), indexing="ij")
    i, j = i.ravel(), j.ravel()
    quads = [(i, j), (i + 1, j), (i + 1, j + 1), (i, j + 1)]
    corners, normals = [], []
    for a, b, c in ((0, 1, 2), (0, 2, 3)):
        corners.append(np.stack([p[quads[k]] for k in (a, b, c)], axis=1))
        normals.append(np.stack([n[quads[k]] for k in (a, b, c)], axis=1))
    corners, normals = np.concatenate(corners), np.concatenate(normals)
    face = np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0])
    keep = np.linalg.norm(face, axis=1) > 1e-14
    # Wind each triangle counter-clockwise seen from outside, where its normals point
    inward = np.einsum("ij,ij->i", face, normals.sum(axis=1)) < 0.0
    corners[inward] = corners[inward][:, ::-1]
    normals[inward] = normals[inward][:, ::-1]
    return corners[keep], normals[keep], np.full(int(keep.sum()), smooth)


def _unit(v):
    return v / np.linalg.norm(v, axis=-1, keepdims=True)


def _disc(z, facing, n_around, rings):
    """A flat cap at height z, normal (0, 0, facing), as a polar grid."""

    def point_normal(u, v):
        c, s = _ring(u)
        r = 1.0 - v
        p = np.stack([r * c, r * s, np.full_like(u, z)], axis=-1)
        return p, np.broadcast_to([0.0, 0.0, float(facing)], p.shape)

    return _grid(point_normal, n_around, rings, False)


def _snap(x):
    """Zero where rounding left a trace (sin pi = 1.2e-16), and -0.0 made 0.0, so that
    points meant to coincide (seams, poles) are identical floats."""
    return np.where(np.abs(x) < 1e-12, 0.0, x) + 0.0


def _ring(turns):
    """cos and sin of `turns` full turns; a whole turn gives exactly the start again."""
    theta = 2.0 * math.pi * np.mod(turns, 1.0)
    return _snap(np.cos(theta)), _snap(np.sin(theta))


def _sphere_patches(n):
    def point_normal(u, v):
        c, s = _ring(u)
        phi = math.pi * v  # from the south pole up
        sin_phi, cos_phi = _snap(np.sin(phi)), _snap(np.cos(phi))
        p = np.stack([sin_phi * c, sin_phi * s, -cos_phi], axis=-1)
        return p, p

    return [_grid(point_normal, n, max(2, n // 2), True)]


def _cylinder_patches(n):
    def side(u, v):
        c, s = _ring(u)
        p = np.stack([c, s, 2.0 * v - 1.0], axis=-1)
        return p, np.stack([c, s, np.zeros_like(c)], axis=-1)

    along = max(1, round(n / math.pi))  # height 2 against a circumference of 2 pi
    rings = max(1, round(n / (2.0 * math.pi)))
    return [_grid(side, n, along, True), _disc(1.0, 1, n, rings), _disc(-1.0, -1, n, rings)]


def _cone_patches(n):
    def side(u, v):
        c, s = _ring(u)
        r = 1.0 - v
        p = np.stack([r * c, r * s, 2.0 * v - 1.0], axis=-1)
        # The gradient of x^2 + y^2 - ((1 - z) / 2)^2 is r (2 cos, 2 sin, 1): the same along
        # a generator, so corners at the apex get their own generator's normal
        return p, _unit(np.stack([2.0 * c, 2.0 * s, np.ones_like(c)], axis=-1))

    along = max(1, round(n * math.sqrt(5.0) / (2.0 * math.pi)))
    rings = max(1, round(n / (2.0 * math.pi)))
    return [_grid(side, n, along, True), _disc(-1.0, -1, n, rings)]


def _torus_patches(n):
    def point_normal(u, v):
        c, s = _ring(u)
        cv, sv = _ring(v)
        radial = np.stack([c * cv, s * cv, sv], axis=-1)
        centre = np.stack([c, s, np.zeros_like(c)], axis=-1) * TORUS_MAJOR
        return centre + TORUS_MINOR * radial, radial

    return [_grid(point_normal, n, max(3, round(n * TORUS_MINOR / TORUS_MAJOR)), True)]


PATCHES = {
    "sphere": _sphere_patches,
    "cylinder": _cylinder_patches,
    "cone": _cone_patches,
    "torus": _torus_patches,
}


def triangle_count(kind, n):
    return sum(len(corners) for corners, _, _ in PATCHES[kind](n))


def resolution_for(kind, triangles):
    """The grid resolution n whose mesh has the triangle count nearest to `triangles`."""
    lo, hi = 3, 3
    while triangle_count(kind, hi) < triangles:
        lo, hi = hi, hi * 2
    while hi - lo > 1:  # the count grows with n
        mid = (lo + hi) // 2
        lo, hi = (mid, hi) if triangle_count(kind, mid) < triangles else (lo, mid)
    return min((lo, hi), key=lambda n: abs(triangle_count(kind, n) - triangles))


def tessellate(kind, triangles):
    """A TriangleMesh of about `triangles` triangles approximating the canonical `kind`."""
    patches = PATCHES[kind](resolution_for(kind, triangles))
    corners = np.concatenate([p[0] for p in patches])
    normals = np.concatenate([p[1] for p in patches])
    smooth = np.concatenate([p[2] for p in patches])
    # Weld the corners that share a position: identical floats, so exact matching works
    vertices, index = np.unique(corners.reshape(-1, 3) + 0.0, axis=0, return_inverse=True)
    return TriangleMesh(
        vertices=vertices,
        triangles=index.reshape(-1, 3),
        smooth=smooth,
        corner_normals=normals,
        name=f"{kind} {len(corners)}",
    )
