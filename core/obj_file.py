"""Reading Wavefront OBJ meshes into a `TriangleMesh`, in numpy (no Python loop over lines).

Read: `v` positions (a fourth w or colour values are ignored), `vt` texture coordinates, `vn`
normals, and `f` faces of three or more corners in any of the forms `v`, `v/t`, `v//n`,
`v/t/n`, with negative (relative) indices; polygons are split into fans. Comments and other
statements (`o`, `g`, `s`, `usemtl`, `mtllib`, ...) are skipped. Faces are smooth shaded, as
the report's meshes were: with the file's normals where every corner has one, else with the
report's vertex normals (the sum of the unit normals of the faces around each vertex).

The file is split into whitespace tokens with a line-break token between lines; every
token's statement is then found by array operations, so a million-face file reads in
seconds.
"""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np

from .model import TriangleMesh

_COMMENT = re.compile(rb"#[^\n]*")
# Stands for a line break among the tokens: a byte no OBJ file holds, and not whitespace
_LINE_BREAK = b"\x01"
# Longer than any number or v/t/n corner in an OBJ file (64-bit indices are 20 digits)
_LONGEST_TOKEN = 80
_TOO_LONG = b"\x02"


class ObjError(ValueError):
    """An OBJ file that cannot be read as a mesh; the message says what is wrong where."""


def read_obj(path: str | Path, name: str | None = None, label: str | None = None) -> TriangleMesh:
    """The mesh in the OBJ file at `path`; errors start with `label` (default: the path)."""
    path = Path(path)
    try:
        data = path.read_bytes()
    except OSError as error:
        raise ObjError(f"cannot read '{path}': {error.strerror}") from None
    return parse_obj(data, name or path.stem, label or str(path))


def parse_obj(data: bytes, name: str = "Mesh", source: str = "OBJ") -> TriangleMesh:
    tokens, keyword, position = _tokenize(data)
    positions, vertices_before = _numbers(tokens, keyword, position, b"v", 3, source)
    if len(positions) == 0:
        raise ObjError(f"{source}: no vertices ('v' lines): not an OBJ mesh")
    uvs, uvs_before = _numbers(tokens, keyword, position, b"vt", 2, source)
    normals, normals_before = _numbers(tokens, keyword, position, b"vn", 3, source)
    is_corner = (keyword == b"f") & (position > 0)
    if not is_corner.any():
        raise ObjError(f"{source}: no faces ('f' lines): not an OBJ mesh")
    corners = _face_corners(tokens[is_corner], source)
    first = np.flatnonzero(position[is_corner] == 1)
    sizes = np.diff(np.append(first, len(corners)))
    if sizes.min() < 3:
        raise ObjError(f"{source}: a face has {sizes.min()} corners; a face needs at least 3")
    fan = _fan(first, sizes)

    def resolve(column, before, count, what):
        return _resolve(corners[:, column], before[is_corner], count, what, source)[fan]

    triangles = resolve(0, vertices_before, len(positions), "vertex")
    corner_uvs = corner_normals = vertex_normals = None
    if len(uvs) and np.all(corners[:, 1] != 0):
        corner_uvs = uvs[resolve(1, uvs_before, len(uvs), "texture coordinate")]
    if len(normals) and np.all(corners[:, 2] != 0):
        corner_normals = normals[resolve(2, normals_before, len(normals), "normal")]
    else:
        vertex_normals = summed_face_normals(positions, triangles)
    return TriangleMesh(
        vertices=positions,
        triangles=triangles,
        smooth=True,
        vertex_normals=vertex_normals,
        corner_normals=corner_normals,
        corner_uvs=corner_uvs,
        name=name,
    )


def summed_face_normals(vertices: np.ndarray, triangles: np.ndarray) -> np.ndarray:
    """The report's vertex normals: the sum of the unit normals of the faces at each vertex,
    normalised (a vertex of no face, or whose faces cancel, gets +z)."""
    corners = vertices[triangles]
    face = np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0])
    length = np.linalg.norm(face, axis=1, keepdims=True)
    face = np.divide(face, length, out=np.zeros_like(face), where=length > 0)
    summed = np.zeros_like(vertices)
    for k in range(3):
        np.add.at(summed, triangles[:, k], face)
    length = np.linalg.norm(summed, axis=1, keepdims=True)
    lone = length[:, 0] == 0
    summed[lone], length[lone] = (0.0, 0.0, 1.0), 1.0
    return summed / length


def _tokenize(data: bytes):
    """(tokens, each token's statement keyword, its position in the statement: 0 for the
    keyword itself); line breaks are dropped."""
    text = _COMMENT.sub(b"", data).replace(b"\r", b" ").replace(b"\\\n", b" ")
    words = [*text.replace(b"\n", b" \x01 ").split(), _LINE_BREAK]
    # numpy sizes every token as the longest: one 2 MB name made 11.6 GiB of tokens. No
    # number or face corner is that long, so a longer token (a name, which is not read)
    # stands as one that reads as no number
    if max(map(len, words)) > _LONGEST_TOKEN:
        words = [w if len(w) <= _LONGEST_TOKEN else _TOO_LONG for w in words]
    words = np.array(words)
    breaks = words == _LINE_BREAK
    first = np.concatenate(([True], breaks[:-1])) & ~breaks
    index = np.arange(len(words))
    statement_start = np.maximum.accumulate(np.where(first, index, 0))
    keep = ~breaks
    return words[keep], words[statement_start][keep], (index - statement_start)[keep]


def _numbers(tokens, keyword, position, name: bytes, width: int, source: str):
    """The first `width` numbers of every `name` statement, (n, width) float64, and per
    token the count of those statements so far (what a relative index counts back from)."""
    statements = (keyword == name) & (position == 0)
    count = int(np.count_nonzero(statements))
    running = np.cumsum(statements)
    if count == 0:
        return np.zeros((0, width)), running
    values = (keyword == name) & (position >= 1) & (position <= width)
    if np.count_nonzero(values) != count * width:
        raise ObjError(
            f"{source}: a '{name.decode()}' line has fewer than {width} numbers; "
            f"every '{name.decode()}' line needs {width}"
        )
    try:
        numbers = tokens[values].astype(np.float64).reshape(count, width)
    except ValueError:
        raise ObjError(f"{source}: a '{name.decode()}' line holds something not a number") from None
    if not np.all(np.isfinite(numbers)):
        raise ObjError(f"{source}: a '{name.decode()}' line holds inf or nan")
    return numbers, running


def _face_corners(words: np.ndarray, source: str) -> np.ndarray:
    """Every face corner as its (vertex, texture, normal) indices as written, 0 where
    absent: `7`, `7/2`, `7//3` and `7/2/3` are padded to three parts, then split at once."""
    slashes = np.char.count(words, b"/")
    if slashes.max() > 2:
        raise ObjError(f"{source}: a face corner has more than two '/'; use v, v/t, v//n or v/t/n")
    padded = np.char.add(words, np.array([b"/0/0", b"/0", b""])[slashes])
    parts = b"/".join(padded.tolist()).replace(b"//", b"/0/").split(b"/")
    try:
        return np.array(parts).astype(np.int64).reshape(-1, 3)
    except ValueError:
        raise ObjError(f"{source}: a face corner is not made of whole numbers") from None
    except OverflowError:  # beyond 64 bits: no file holds that many vertices
        raise ObjError(f"{source}: a face corner's index is beyond any vertex count") from None


def _fan(line_starts: np.ndarray, sizes: np.ndarray) -> np.ndarray:
    """(t, 3) corner indices splitting each polygon (first corner, size) into a fan."""
    per_face = sizes - 2
    face = np.repeat(np.arange(len(sizes)), per_face)
    step = np.arange(len(face)) - np.repeat(np.cumsum(per_face) - per_face, per_face)
    first = line_starts[face]
    return np.stack([first, first + step + 1, first + step + 2], axis=1)


def _resolve(index, before, count, what, source) -> np.ndarray:
    """OBJ's 1-based and negative (relative to the entries so far) indices into 0-based
    ones, checked."""
    resolved = np.where(index > 0, index - 1, before + index)
    bad = (resolved < 0) | (resolved >= count) | (index == 0)
    if bad.any():
        raise ObjError(
            f"{source}: a face refers to {what} {int(index[bad][0])}, which the file does not "
            f"have ({count} in all)"
        )
    return resolved
