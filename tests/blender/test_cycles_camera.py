"""Camera › Depth of Field › Aperture as Cycles reads it: Blades (polygonal bokeh), Rotation
and Ratio (anamorphic bokeh). A tiny glowing ball far in front of the plane in focus is drawn
as the aperture's own shape, scaled: its blur in Whitted must cover the pixels Cycles'
covers, with the same spread along each axis and the same light in all. (The same blur with
a round aperture misses Cycles' pentagon: it is checked too, so the test can tell.)"""

import math

import numpy as np
import pytest

from tests.support.cycles import add_ball, new_scene, node_material, render_with

pytestmark = pytest.mark.bpy
SIZE = 64
# Covered pixels shared over covered by either: measured 0.985-0.992 for Whitted's blur and
# Cycles' of each aperture below, 0.905 for a round blur of a pentagon's area
SAME_SHAPE = 0.96


def bokeh_scene(bpy, blades, rotation, ratio):
    scene = new_scene(bpy)
    bpy.data.objects.remove(bpy.data.objects["Plane"])
    scene.render.resolution_x = scene.render.resolution_y = SIZE
    camera = scene.camera.data
    camera.type, camera.lens, camera.sensor_width = "PERSP", 50.0, 36.0
    camera.dof.use_dof = True
    camera.dof.focus_distance = 10.0
    camera.dof.aperture_fstop = 0.05  # a lens 0.5 across: the ball's blur is ~35 px wide
    camera.dof.aperture_blades = blades
    camera.dof.aperture_rotation = rotation
    camera.dof.aperture_ratio = ratio
    glow, _ = node_material(bpy, "Glow", "ShaderNodeEmission", Color=(1.0, 1.0, 1.0),
                            Strength=100.0)  # fmt: skip
    # 2 px across, in front of a blur 35 px across: the blur is the aperture's shape, but
    # only one lens point in 60 sees the ball, hence the many samples
    ball = add_ball(bpy, scene, glow, location=(0.3, -0.2, 8.0), radius=0.05)
    ball.visible_diffuse = False
    scene.whitted.pixel_samples = 48  # 2,304 lens points per pixel
    return scene


def covered(image):
    """The pixels the blur covers: above a third of its mean brightness inside, after a 3 x 3
    box filter (each renderer's noise smoothed alike)."""
    brightness = image.sum(axis=-1)
    padded = np.pad(brightness, 1)
    brightness = sum(
        padded[1 + dy : 1 + dy + SIZE, 1 + dx : 1 + dx + SIZE]
        for dy in (-1, 0, 1)
        for dx in (-1, 0, 1)
    )
    return brightness > brightness[brightness > 0.05 * brightness.max()].mean() / 3.0


def spread(mask):
    """The covered pixels' centre and the covariance of their positions."""
    rows, columns = np.nonzero(mask)
    points = np.stack([columns, rows]).astype(float)
    return points.mean(axis=1), np.cov(points)


def overlap(a, b):
    return (a & b).sum() / (a | b).sum()


@pytest.mark.parametrize(
    "blades, rotation, ratio",
    [(5, 0.3, 1.0), (6, 0.0, 0.6), (3, -1.0, 1.5)],
    ids=["pentagon", "anamorphic hexagon", "tall triangle"],
)
def test_the_aperture_shapes_the_blur_as_in_cycles(
    bpy_with_whitted, tmp_path, blades, rotation, ratio
):
    bpy = bpy_with_whitted
    scene = bokeh_scene(bpy, blades, rotation, ratio)
    cycles = render_with(bpy, scene, "CYCLES", tmp_path / "cycles.exr", samples=4096)
    whitted = render_with(bpy, scene, "WHITTED", tmp_path / "whitted.exr")
    assert 0.9 < whitted.sum() / cycles.sum() < 1.1  # the same light, spread the same way
    shape_c, shape_w = covered(cycles), covered(whitted)
    assert 150 < shape_c.sum() < 0.6 * SIZE * SIZE  # the probe: a blur, inside the frame
    assert overlap(shape_c, shape_w) > SAME_SHAPE, overlap(shape_c, shape_w)
    (centre_c, cov_c), (centre_w, cov_w) = spread(shape_c), spread(shape_w)
    np.testing.assert_allclose(centre_w, centre_c, atol=0.5)
    np.testing.assert_allclose(cov_w, cov_c, atol=0.05 * np.abs(cov_c).max())


def test_a_round_aperture_does_not_pass_for_a_pentagon(bpy_with_whitted, tmp_path):
    """What the test above would see if Blades were ignored: the round blur's outline misses
    the pentagon's by more than the test allows."""
    bpy = bpy_with_whitted
    scene = bokeh_scene(bpy, 5, 0.3, 1.0)
    pentagon = covered(render_with(bpy, scene, "CYCLES", tmp_path / "cycles.exr", samples=512))
    scene.camera.data.dof.aperture_blades = 0
    # A disk of the pentagon's area: the test's threshold, not the size, must tell them apart
    scene.camera.data.dof.aperture_fstop = 0.05 / math.sqrt(
        5 / 2 * math.sin(2 * math.pi / 5) / math.pi
    )
    disk = covered(render_with(bpy, scene, "WHITTED", tmp_path / "whitted.exr"))
    assert overlap(pentagon, disk) < SAME_SHAPE


@pytest.mark.parametrize("kind", ["ORTHO", "PERSP"])
def test_clip_end_hides_what_lies_beyond_as_in_cycles(bpy_with_whitted, tmp_path, kind):
    """Camera › Clip End 9.4, the camera 10 above the plane and a ball of radius 1 on it:
    the plane is gone (the grey World in its place) and only the ball's cap above 0.6 is
    seen, a disk whose edge both renderers put at the same pixels. (Before: the whole ball
    and the plane were drawn, Clip End ignored.)"""
    bpy = bpy_with_whitted
    scene = new_scene(bpy)
    scene.world.color = (0.3, 0.3, 0.3)
    if scene.world.node_tree is not None:
        background = scene.world.node_tree.nodes["Background"]
        background.inputs[0].default_value = (0.3, 0.3, 0.3, 1.0)
        background.inputs[1].default_value = 1.0
    glow, _ = node_material(bpy, "Glow", "ShaderNodeEmission", Color=(1.0, 0.2, 0.1),
                            Strength=1.0)  # fmt: skip
    add_ball(bpy, scene, glow, location=(0.0, 0.0, 0.0), radius=1.0)
    camera = scene.camera.data
    camera.type, camera.lens, camera.clip_end = kind, 50.0, 9.4
    if kind == "PERSP":
        camera.sensor_width = 24.0  # a 2.8-unit view at the ball's top: its cap is 21 px across
    cycles = render_with(bpy, scene, "CYCLES", tmp_path / "cycles.exr", 16)
    whitted = render_with(bpy, scene, "WHITTED", tmp_path / "whitted.exr")
    cap_cycles, cap_whitted = cycles[..., 1] < 0.25, whitted[..., 1] < 0.25  # red, not grey
    print(f"{kind}: cap {cap_cycles.sum()} / {cap_whitted.sum()} px")
    assert 10 < cap_cycles.sum() < 0.5 * cap_cycles.size  # the premise: a cap, no plane
    assert np.abs(whitted[~cap_cycles & ~cap_whitted] - 0.3).max() < 1e-3  # the World, no plane
    assert (cap_whitted != cap_cycles).mean() < 0.02
