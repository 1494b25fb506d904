"""The OBJ reader: every face form, relative indices, polygons, normals, and clear errors."""

import re

import numpy as np
import pytest

from core.obj_file import ObjError, parse_obj, read_obj

SQUARE = b"""# a unit square as one quad
v 0 0 0
v 1 0 0
v 1 1 0 1.0
v 0 1 0
vt 0 0
vt 1 0
vt 1 1
vt 0 1
vn 0 0 1
"""


@pytest.mark.parametrize(
    "face",
    [b"f 1 2 3 4", b"f 1/1 2/2 3/3 4/4", b"f 1//1 2//1 3//1 4//1", b"f 1/1/1 2/2/1 3/3/1 4/4/1",
     b"f -4/-4/-1 -3/-3/-1 -2/-2/-1 -1/-1/-1", b"  f\t1/1/1 2/2/1   3/3/1 4/4/1  # quad"],
)  # fmt: skip
def test_every_face_form_gives_the_same_fan(face):
    mesh = parse_obj(SQUARE + face + b"\n")
    np.testing.assert_array_equal(mesh.triangles, [[0, 1, 2], [0, 2, 3]])
    np.testing.assert_array_equal(mesh.vertices[2], [1, 1, 0])
    if b"/" in face and not face.split()[1].count(b"//"):
        np.testing.assert_array_equal(mesh.corner_uvs[1], [[0, 0], [1, 1], [0, 1]])
    else:
        assert mesh.corner_uvs is None
    if face.count(b"/") >= 8:
        np.testing.assert_array_equal(mesh.corner_normals, np.tile([0.0, 0, 1], (2, 3, 1)))
        assert mesh.vertex_normals is None
    else:
        np.testing.assert_allclose(mesh.vertex_normals, np.tile([0.0, 0, 1], (4, 1)))


def test_relative_indices_count_back_from_their_own_line():
    mesh = parse_obj(b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf -3 -2 -1\nv 5 5 5\nf -4 -3 -1\n")
    np.testing.assert_array_equal(mesh.triangles, [[0, 1, 2], [0, 1, 3]])


def test_polygons_split_into_fans_of_their_own_size():
    hexagon = b"".join(b"v %f %f 0\n" % (np.cos(a), np.sin(a)) for a in np.arange(6) * np.pi / 3)
    mesh = parse_obj(hexagon + b"f 1 2 3\nf 1 2 3 4 5 6\nf 4 5 6\n")
    np.testing.assert_array_equal(
        mesh.triangles, [[0, 1, 2], [0, 1, 2], [0, 2, 3], [0, 3, 4], [0, 4, 5], [3, 4, 5]]
    )


def test_vertex_normals_are_the_reports_sum_of_face_normals():
    """At each vertex of a tetrahedron, the normalised sum of its three unit face normals
    (computed here face by face)."""
    points = np.array([[0.0, 0, 0], [2, 0, 0], [0, 1, 0], [0, 0, 3]])
    faces = [(0, 2, 1), (0, 1, 3), (0, 3, 2), (1, 2, 3)]
    # floats, not numpy scalars, whose repr is `np.float64(2.0)` under numpy 2
    text = b"".join(b"v %r %r %r\n" % tuple(map(float, p)) for p in points)
    text += b"".join(b"f %d %d %d\n" % tuple(i + 1 for i in f) for f in faces)
    mesh = parse_obj(text)
    for vertex in range(4):
        total = np.zeros(3)
        for a, b, c in faces:
            if vertex in (a, b, c):
                n = np.cross(points[b] - points[a], points[c] - points[a])
                total += n / np.linalg.norm(n)
        np.testing.assert_allclose(mesh.vertex_normals[vertex], total / np.linalg.norm(total))


def test_the_committed_box_is_a_closed_solid():
    from tests.core.cs488.test_scenes import SCENES

    mesh = read_obj(SCENES / "box.obj")
    assert mesh.open_edge_count() == 0 and len(mesh.triangles) == 12
    assert mesh.corner_uvs.shape == (12, 3, 2) and mesh.corner_normals.shape == (12, 3, 3)


@pytest.mark.parametrize(
    "text, message",
    [
        (b"hello\n", "no vertices ('v' lines)"),
        (b"v 0 0 0\n", "no faces ('f' lines)"),
        (b"v 0 0\nf 1 1 1\n", "a 'v' line has fewer than 3 numbers"),
        (b"v 0 0 x\nf 1 1 1\n", "a 'v' line holds something not a number"),
        (b"v 0 0 nan\nf 1 1 1\n", "a 'v' line holds inf or nan"),
        (b"v 0 0 0\nv 1 0 0\nf 1 2\n", "a face has 2 corners; a face needs at least 3"),
        (b"v 0 0 0\nf 1 2 3\n", "a face refers to vertex 2, which the file does not have (1 in"),
        (b"v 0 0 0\nf 0 1 1\n", "a face refers to vertex 0"),
        (b"v 0 0 0\nf 1/a 1 1\n", "a face corner is not made of whole numbers"),
        (b"v 0 0 0\nf 1/1/1/1 1 1\n", "a face corner has more than two '/'"),
    ],
)
def test_bad_files_say_what_is_wrong(text, message):
    with pytest.raises(ObjError, match="^mesh\\.obj: " + re.escape(message)):
        parse_obj(text, source="mesh.obj")


def test_a_long_name_does_not_size_every_token():
    """numpy sizes an array of byte strings by its longest: a 2 MB object name asked for
    11.6 GiB of tokens. The mesh still reads, and no token is stored longer than a number."""
    from core.obj_file import _tokenize

    data = b"o " + b"n" * 2_000_000 + b"\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"
    tokens, _, _ = _tokenize(data)
    assert tokens.dtype.itemsize <= 80
    assert len(parse_obj(data).triangles) == 1
