"""Blender fixtures: the bpy 5.0 module with the add-on enabled the way Blender loads it."""

import os
import shutil
import subprocess

import pytest

from tests.support import ROOT  # also the Blender tests' (imported from here)

SAMPLE = ROOT / "sample_blends" / "spheres.blend"


@pytest.fixture(scope="session")
def bpy_with_whitted():
    bpy = pytest.importorskip("bpy")
    import addon_utils

    module = addon_utils.enable("whitted", default_set=True, handle_error=None)
    assert module is not None, "the whitted add-on did not load (see the traceback above)"
    return bpy


@pytest.fixture
def sample_scene(bpy_with_whitted):
    """The sample scene, freshly opened, rendered at half size for speed."""
    bpy = bpy_with_whitted
    bpy.ops.wm.open_mainfile(filepath=str(SAMPLE))
    scene = bpy.context.scene
    scene.render.resolution_percentage = 50
    return scene


def clear_scene(bpy):
    """Remove every object and its geometry from the open file, keeping the add-on enabled
    (reading factory settings would unregister it)."""
    for obj in list(bpy.data.objects):
        bpy.data.objects.remove(obj)
    for collection in (bpy.data.meshes, bpy.data.curves, bpy.data.metaballs):
        for datablock in list(collection):
            collection.remove(datablock)
    return bpy.context.scene


def pytest_collection_modifyitems(items):
    """Every test that loads bpy is marked `bpy`: those run in each Blender version's
    environment (tests/blender/versions.py)."""
    for item in items:
        if "bpy_with_whitted" in getattr(item, "fixturenames", ()):
            item.add_marker(pytest.mark.bpy)


@pytest.fixture
def display():
    """A fresh X server of its own (the display number it chose)."""
    xvfb = shutil.which("Xvfb")
    assert xvfb, "no Xvfb on PATH: run `make setup`, which installs Debian's xvfb"
    read, write = os.pipe()
    server = subprocess.Popen(
        [xvfb, "-displayfd", str(write), "-screen", "0", "1280x800x24", "-nolisten", "tcp"],
        pass_fds=(write,), stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
    )  # fmt: skip
    os.close(write)
    with os.fdopen(read) as chosen:
        number = chosen.readline().strip()
    yield f":{number}"
    server.kill()
    server.wait()
