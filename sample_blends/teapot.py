"""Newell's teapot tessellated from its Bezier patches (numpy only, no Blender).

Each bicubic patch is evaluated on an (n+1) x (n+1) grid of its (s, t) parameters and split
into 2 n^2 triangles. Points shared by neighbouring patches are welded, so smooth shading
sees one surface; the triangles the lid's and bottom's collapsed patch corners would make
(two welded corners) are dropped.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np

DATA = Path(__file__).resolve().parent / "newell_teapot.txt"
# Points closer than this (in the data's units, the teapot is about 6 wide) are one point
WELD_TOLERANCE = 1e-5


@dataclass(frozen=True)
class TeapotMesh:
    vertices: np.ndarray  # (v, 3) float64, z up, the body's base at z = 0
    triangles: np.ndarray  # (t, 3) int64 indices into vertices
    corner_uvs: np.ndarray  # (t, 3, 2) the patch parameters (s, t) at each corner


def read_patches(path: Path = DATA) -> np.ndarray:
    """(patches, 4, 4, 3) control points."""
    lines = [line for line in path.read_text().splitlines() if not line.startswith("#")]
    patch_count = int(lines[0])
    indices = np.array(
        [[int(i) - 1 for i in line.split(",")] for line in lines[1 : 1 + patch_count]]
    )
    point_count = int(lines[1 + patch_count])
    points = np.array([[float(c) for c in line.split(",")] for line in lines[2 + patch_count :]])
    if indices.shape != (patch_count, 16) or points.shape != (point_count, 3):
        raise ValueError(f"{path}: malformed patch data")
    return points[indices].reshape(patch_count, 4, 4, 3)


def _bernstein(u: np.ndarray) -> np.ndarray:
    """(len(u), 4) cubic Bernstein basis values."""
    u = u[:, None]
    k = np.arange(4)
    binomial = np.array([1.0, 3.0, 3.0, 1.0])
    return binomial * u**k * (1.0 - u) ** (3 - k)


def tessellate(segments: int = 10, path: Path = DATA) -> TeapotMesh:
    patches = read_patches(path)
    u = np.linspace(0.0, 1.0, segments + 1)
    basis = _bernstein(u)
    # points[p, i, j] = sum_ab B_a(u_i) B_b(u_j) P[p, a, b]
    grid = np.einsum("ia,jb,pabc->pijc", basis, basis, patches)
    flat = grid.reshape(-1, 3)
    keys = np.round(flat / WELD_TOLERANCE).astype(np.int64)
    _, first, welded = np.unique(keys, axis=0, return_index=True, return_inverse=True)
    welded = welded.reshape(len(patches), segments + 1, segments + 1)
    i, j = np.meshgrid(np.arange(segments), np.arange(segments), indexing="ij")
    i, j = i.ravel(), j.ravel()
    corners = [(i, j), (i + 1, j), (i + 1, j + 1), (i, j + 1)]
    quads = np.stack([welded[:, a, b] for a, b in corners], axis=-1)  # (p, q, 4)
    quad_uvs = np.stack([np.stack([u[a], u[b]], -1) for a, b in corners], axis=-2)
    quad_uvs = np.broadcast_to(quad_uvs, (len(patches), *quad_uvs.shape))
    # The data's patches wind clockwise seen from outside: (0, 2, 1) faces outward
    triangles = np.concatenate([quads[..., [0, 2, 1]], quads[..., [0, 3, 2]]], axis=1)
    uvs = np.concatenate([quad_uvs[..., [0, 2, 1], :], quad_uvs[..., [0, 3, 2], :]], axis=1)
    triangles, uvs = triangles.reshape(-1, 3), uvs.reshape(-1, 3, 2)
    distinct = (
        (triangles[:, 0] != triangles[:, 1])
        & (triangles[:, 1] != triangles[:, 2])
        & (triangles[:, 0] != triangles[:, 2])
    )
    return TeapotMesh(flat[first], triangles[distinct], uvs[distinct])


def write_obj(path: Path, segments: int = 10) -> Path:
    """The teapot as an OBJ file for CS488 scripts (final_scene.lua): y up, as those scenes
    are, the body's base at y = 0; positions only, so the loader smooths it the report's
    way."""
    mesh = tessellate(segments)
    x, y, z = mesh.vertices.T
    lines = ["# Newell's teapot, tessellated by sample_blends/teapot.py (y up)"]
    lines += [f"v {a:.6f} {b:.6f} {c:.6f}" for a, b, c in zip(x, z, -y, strict=True)]
    lines += [f"f {a} {b} {c}" for a, b, c in (mesh.triangles + 1).tolist()]
    path.write_text("\n".join(lines) + "\n")
    return path


if __name__ == "__main__":
    print(write_obj(Path(__file__).resolve().parent / "teapot.obj"))
