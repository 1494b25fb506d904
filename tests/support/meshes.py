"""Meshes made in numpy for tests and benchmarks: closed, with known geometry."""

import numpy as np


def icosphere(subdivisions: int = 2):
    """A closed unit icosphere: (vertices, triangles), counter-clockwise from outside."""
    g = (1.0 + 5**0.5) / 2.0
    v = np.array(
        [[-1, g, 0], [1, g, 0], [-1, -g, 0], [1, -g, 0], [0, -1, g], [0, 1, g],
         [0, -1, -g], [0, 1, -g], [g, 0, -1], [g, 0, 1], [-g, 0, -1], [-g, 0, 1]],
        float,
    )  # fmt: skip
    f = np.array(
        [[0, 11, 5], [0, 5, 1], [0, 1, 7], [0, 7, 10], [0, 10, 11], [1, 5, 9], [5, 11, 4],
         [11, 10, 2], [10, 7, 6], [7, 1, 8], [3, 9, 4], [3, 4, 2], [3, 2, 6], [3, 6, 8],
         [3, 8, 9], [4, 9, 5], [2, 4, 11], [6, 2, 10], [8, 6, 7], [9, 8, 1]],
    )  # fmt: skip
    v /= np.linalg.norm(v, axis=1, keepdims=True)
    for _ in range(subdivisions):
        edges = np.sort(np.concatenate([f[:, [0, 1]], f[:, [1, 2]], f[:, [2, 0]]]), axis=1)
        unique, inverse = np.unique(edges, axis=0, return_inverse=True)
        mid = v[unique].mean(axis=1)
        mid /= np.linalg.norm(mid, axis=1, keepdims=True)
        m = inverse.reshape(3, -1) + len(v)
        a, b, c = f.T
        ab, bc, ca = m
        f = np.concatenate(
            [np.stack(x, axis=1) for x in ((a, ab, ca), (b, bc, ab), (c, ca, bc), (ab, bc, ca))]
        )
        v = np.vstack([v, mid])
    return v, f


def bumpy_cube_sphere(n: int, bump: float = 0.05, seed: int = 7):
    """A closed sphere made of six n x n grids (12 n^2 triangles) with radial bumps, so the
    BVH sees a realistic, uneven surface. n = 289 gives about a million triangles."""
    t = np.linspace(-1.0, 1.0, n + 1)
    a, b = np.meshgrid(t, t, indexing="ij")
    faces = []
    for axis in range(3):
        for sign in (-1.0, 1.0):
            p = np.empty((n + 1, n + 1, 3))
            p[..., axis] = sign
            p[..., (axis + 1) % 3] = a * sign
            p[..., (axis + 2) % 3] = b
            faces.append(p.reshape(-1, 3))
    points = np.concatenate(faces)
    # Weld the shared borders of the six grids so the surface is closed
    rounded = np.round(points * n).astype(np.int64)
    _, first, inverse = np.unique(rounded, axis=0, return_index=True, return_inverse=True)
    vertices = points[first]
    vertices /= np.linalg.norm(vertices, axis=1, keepdims=True)
    rng = np.random.default_rng(seed)
    k = rng.normal(size=(6, 3)) * 3
    phase = rng.uniform(0, 2 * np.pi, size=6)
    radius = 1.0 + bump * np.sin(vertices @ k.T + phase).mean(axis=1)
    vertices *= radius[:, None]
    grid = np.arange((n + 1) * (n + 1)).reshape(n + 1, n + 1)
    quads = np.stack([grid[:-1, :-1], grid[1:, :-1], grid[1:, 1:], grid[:-1, 1:]], axis=-1).reshape(
        -1, 4
    )
    tris = []
    for face in range(6):
        q = inverse.ravel()[quads + face * (n + 1) * (n + 1)]
        tris += [q[:, [0, 1, 2]], q[:, [0, 2, 3]]]
    triangles = np.concatenate(tris)
    # Orient every triangle outward
    v0, v1, v2 = (vertices[triangles[:, k]] for k in range(3))
    outward = np.einsum("ij,ij->i", np.cross(v1 - v0, v2 - v0), v0 + v1 + v2) > 0
    triangles[~outward] = triangles[~outward][:, ::-1]
    return vertices, triangles
