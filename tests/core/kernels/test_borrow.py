"""Borrowing (core.kernels.borrow) rebuilds the packed scene and the workspace with every
array unowned. Checked from outside: each field of the borrowed value is a view of the
original field of the same name (same data address, shape, strides and dtype), nothing is
left out or swapped, and the numba types are those of the originals, so no kernel compiles
twice."""

import numba
import numpy as np
import pytest

from core import AreaLight, Material, Mesh, PointLight, Scene, Sphere, Texture, TriangleMesh
from core.compile import pack_scene
from core.jit.decorators import kernel
from core.kernels.borrow import borrowed
from core.kernels.workspace import new_workspace
from core.model import RenderSettings
from tests.support.meshes import icosphere

pytestmark = pytest.mark.skipif(
    numba.config.DISABLE_JIT, reason="without the JIT nothing is borrowed (borrowed(x) is x)"
)


@kernel
def _borrow_for_test(value):
    # Returned only so the test can look at it: the caller keeps the original alive
    return borrowed(value)


def _packed_scene():
    vertices, triangles = icosphere(1)
    checker = np.zeros((2, 2, 3))
    checker[0, 0] = 1.0
    shapes = [
        Sphere("S", Material(texture=Texture(pixels=checker))),
        Mesh("M", mesh=TriangleMesh(vertices, triangles)),
    ]
    lights = [
        PointLight((0.0, 0.0, 5.0), (1.0, 1.0, 1.0)),
        AreaLight((0.0, 0.0, 4.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (5.0, 5.0, 5.0)),
    ]
    return pack_scene(Scene(shapes=shapes, lights=lights), RenderSettings(8, 8))


def _leaves(value, path=""):
    """(path, array) for every array in a tree of named tuples, in field order."""
    if isinstance(value, np.ndarray):
        return [(path, value)]
    assert isinstance(value, tuple), f"{path}: {type(value).__name__} is not an array or tuple"
    names = getattr(value, "_fields", range(len(value)))
    return [
        leaf for name, v in zip(names, value, strict=True) for leaf in _leaves(v, f"{path}.{name}")
    ]


def _same_tree_of_views(original, copy):
    assert type(copy) is type(original)
    pairs = list(zip(_leaves(original), _leaves(copy), strict=True))
    for (path, a), (copy_path, b) in pairs:
        assert copy_path == path
        assert b is not a and b.base is None, f"{path} came back owned: it was not borrowed"
        assert b.__array_interface__["data"][0] == a.__array_interface__["data"][0], path
        assert (b.shape, b.strides, b.dtype) == (a.shape, a.strides, a.dtype), path
    return len(pairs)


@pytest.mark.parametrize("make", [_packed_scene, lambda: new_workspace(4, 4)], ids=["scene", "ws"])
def test_borrowed_value_views_every_field_of_the_original_in_its_place(make):
    original = make()
    copy = _borrow_for_test(original)
    assert _same_tree_of_views(original, copy) > 10
    assert numba.typeof(copy) == numba.typeof(original)


def test_a_named_tuple_of_one_array_type_keeps_its_order():
    # Lights holds ten float64 (k, 3) arrays: a swap by position would still compile
    lights = _packed_scene().lights
    copy = _borrow_for_test(lights)
    for name in lights._fields:
        a, b = getattr(lights, name), getattr(copy, name)
        assert b.__array_interface__["data"][0] == a.__array_interface__["data"][0], name
