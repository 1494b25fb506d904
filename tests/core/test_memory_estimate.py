"""Memory is estimated before it is allocated: the estimate's parts in closed form, a render
past the machine's memory refused naming its largest part and what to change, and the
figures checked against what packing really takes (peak resident memory, in a process of
its own), so that an estimate below the truth fails here."""

import subprocess
import sys

import numpy as np
import pytest

import core
from core import memory_estimate
from core.compile import compile_scene
from core.memory_estimate import check_fits, estimate
from tests.core.cs488.test_hostile_scripts import one_colour_png
from tests.support import ROOT


def scene_of(shapes):
    camera = core.Camera(eye=(0, 0, 5), view=(0, 0, -1), up=(0, 1, 0), fovy=50)
    return core.Scene(camera, shapes, [core.PointLight(position=(0, 3, 3))])


def random_mesh(triangles: int) -> core.TriangleMesh:
    rng = np.random.default_rng(1)
    return core.TriangleMesh(
        vertices=rng.random((3 * triangles, 3)), triangles=np.arange(3 * triangles).reshape(-1, 3)
    )


def test_the_parts_count_shared_meshes_and_textures_once():
    mesh = random_mesh(10)
    texture = core.Texture(pixels=np.zeros((30, 20, 3), np.float32))
    material = core.Material(texture=texture)
    shapes = [core.Mesh(f"m{i}", material, mesh=mesh) for i in range(5)] + [core.Sphere()]
    settings = core.RenderSettings(40, 30, max_depth=7, shadow_samples=9, threads=2)
    parts = estimate(shapes, settings).parts
    assert parts["meshes"] == 10 * memory_estimate.TRIANGLE_PEAK_BYTES
    assert parts["textures"] == 600 * (memory_estimate.TEXEL_BYTES
                                       + memory_estimate.TEXEL_LOADING_BYTES)  # fmt: skip
    assert parts["image"] == 1200 * memory_estimate.PIXEL_BYTES
    assert parts["shapes"] == 6 * memory_estimate.SHAPE_BYTES
    assert parts["ray stacks"] == 2 * (memory_estimate.WORKSPACE_BYTES + 9 * 80 + 9 * 40)


def test_a_render_past_the_machines_memory_is_refused_naming_its_largest_part():
    shapes = [core.Mesh("m", core.Material(), mesh=random_mesh(10))]
    needed = estimate(shapes, core.RenderSettings(8, 8))
    check_fits(needed, memory=needed.total)  # exactly fits
    big = memory_estimate.MemoryEstimate({**needed.parts, "meshes": 40 * 2**30}, needed.counts)
    with pytest.raises(core.SceneError) as caught:
        check_fits(big, memory=24 * 2**30)
    message = str(caught.value)
    assert message.startswith("scene: meshes: the render needs about 40.0 GiB (meshes 40.0 GiB")
    assert "more than this machine's 24.0 GiB of memory; use fewer or simpler meshes" in message


def test_a_texture_file_is_sized_from_its_header_and_refused_before_it_is_read(
    tmp_path, monkeypatch
):
    """8000 x 8000 pixels in a file of a few kilobytes: 7.9 GiB to load. The machine is said
    to have 4 GiB, and the file's pixels must not be decoded."""
    (tmp_path / "big.png").write_bytes(one_colour_png(8000, 8000))
    material = core.Material(texture=core.Texture(path=tmp_path / "big.png"))
    monkeypatch.setattr(memory_estimate, "machine_memory", lambda: 4 * 2**30)
    decoded = []
    monkeypatch.setattr("core.compile.materials.load_texture", lambda *a: decoded.append(a))
    with pytest.raises(core.SceneError, match=r"^scene: textures: the render needs about 7\.9 GiB"):
        compile_scene(scene_of([core.Sphere(material=material)]), core.RenderSettings(8, 8))
    assert not decoded


# Runs in a process of its own: the peak resident memory packing takes, over what the
# process held before (Linux's VmHWM, reset first), next to the estimate of it
PEAK = """
import sys
import numpy as np
import core
from core.memory_estimate import estimate
from core.compile import compile_scene
from tests.core.test_memory_estimate import random_mesh, scene_of
kind = sys.argv[1]
small = scene_of([core.Sphere()])
compile_scene(small, core.RenderSettings(8, 8))  # the kernels, loaded before measuring
if kind == "mesh":
    shapes = [core.Mesh("m", core.Material(), mesh=random_mesh(400_000))]
else:
    texture = core.Texture(pixels=np.random.default_rng(1).random((2000, 2000, 3)))
    shapes = [core.Sphere(material=core.Material(texture=texture))]
scene, settings = scene_of(shapes), core.RenderSettings(8, 8, threads=1)
def status(field):  # bytes
    text = open("/proc/self/status").read()
    return int(text.split(field + ":")[1].split()[0]) * 1024
with open("/proc/self/clear_refs", "w") as clear:
    clear.write("5")  # the peak (VmHWM) starts again from the resident size now
before = status("VmRSS")
compile_scene(scene, settings)
print(status("VmHWM") - before, estimate(shapes, settings).total)
"""


@pytest.mark.parametrize("kind", ["mesh", "texture"])
def test_the_estimate_is_not_below_what_packing_takes(kind):
    run = subprocess.run([sys.executable, "-c", PEAK, kind], cwd=ROOT, capture_output=True,
                         text=True, timeout=300)  # fmt: skip
    assert run.returncode == 0, run.stderr
    used, estimated = map(int, run.stdout.split())
    assert used <= estimated <= 3 * used + 2**24, (used, estimated)
