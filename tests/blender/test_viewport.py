"""The rendered viewport's update path, driven as Blender drives it (view_update, then
view_draw's view checks), without a window: the view is the scene camera's matrices, as a 3D
view in camera view has them. Its picture is checked against the independent reference
tracer; its re-exports are counted."""

import math
import sys
import threading

import numpy as np
import pytest

from tests.support.blender_reference import expected_pixels, sample_grid, srgb_8bit

pytestmark = pytest.mark.bpy

LAST = 4  # the index of the last of core.progressive.PASSES


def modules():
    return sys.modules["whitted.engine.viewport"], sys.modules["whitted.export"]


def camera_view(bpy, scene, perspective="CAMERA", clip_end=100.0):
    """The View a 3D view looking through the scene camera has, at the render's size."""
    _, export = modules()
    width = scene.render.resolution_x * scene.render.resolution_percentage // 100
    height = scene.render.resolution_y * scene.render.resolution_percentage // 100
    depsgraph = bpy.context.evaluated_depsgraph_get()
    camera = scene.camera.evaluated_get(depsgraph)
    rows = export.view._rows
    return export.view.View(
        width=width,
        height=height,
        view_matrix=rows(camera.matrix_world.inverted()),
        window_matrix=rows(camera.calc_matrix_camera(depsgraph, x=width, y=height)),
        perspective=perspective,
        clip_end=clip_end,
        border=None,
    )


@pytest.fixture
def session(sample_scene, bpy_with_whitted):
    viewport, _ = modules()
    images = []
    session = viewport.ViewportSession(on_image=images.append)
    session.images = images
    yield session
    session.close()


def finish(session, pass_index=LAST):
    image = session.renderer.wait_for(session.renderer.generation, pass_index)
    assert session.error is None and session.renderer.error is None, session.status()
    assert image is not None
    return image


def test_the_viewport_through_the_camera_matches_the_reference_tracer(
    session, sample_scene, bpy_with_whitted
):
    bpy = bpy_with_whitted
    session.update(bpy.context.evaluated_depsgraph_get(), camera_view(bpy, sample_scene))
    image = finish(session)
    pixels = sample_grid(160, 120, 6)
    expected = expected_pixels(sample_scene, pixels)
    got = np.array([srgb_8bit(image.pixels[py, px, :3]) for px, py in pixels])
    np.testing.assert_allclose(got, expected, atol=1.6)


def test_a_coarse_image_comes_before_the_fine_one(session, sample_scene, bpy_with_whitted):
    bpy = bpy_with_whitted
    session.update(bpy.context.evaluated_depsgraph_get(), camera_view(bpy, sample_scene))
    finish(session)
    complete = [image.pass_index for image in session.images if image.complete]
    assert complete == [0, 1, 2, 3, 4]
    first = next(image for image in session.images if image.complete)
    # 1/8 of the size: blocks of 8 x 8 equal pixels
    block = first.pixels[:8, :8].reshape(-1, 4)
    assert np.all(block == block[0])


def test_a_moved_object_reexports_no_mesh_and_the_picture_follows(
    session, sample_scene, bpy_with_whitted
):
    bpy = bpy_with_whitted
    view = camera_view(bpy, sample_scene)
    session.update(bpy.context.evaluated_depsgraph_get(), view)
    before = finish(session).pixels.copy()
    conversions = session.meshes.conversions
    ball = next(o for o in sample_scene.objects if o.type == "MESH")
    ball.location.x += 0.5
    session.update(bpy.context.evaluated_depsgraph_get(), view)
    after = finish(session).pixels
    assert session.meshes.conversions == conversions  # a transform, not a mesh, changed
    assert session.exports == 2
    assert np.abs(after - before).max() > 0.1


def test_an_edited_mesh_is_the_only_mesh_read_again(session, bpy_with_whitted):
    bpy = bpy_with_whitted
    scene = bpy.context.scene
    bpy.ops.mesh.primitive_cube_add(size=1.0, location=(0.0, 0.0, 0.0))
    bpy.ops.mesh.primitive_cube_add(size=1.0, location=(2.0, 0.0, 0.0))
    edited = bpy.context.active_object
    view = camera_view(bpy, scene)
    session.update(bpy.context.evaluated_depsgraph_get(), view)
    finish(session, 0)
    conversions = session.meshes.conversions
    edited.data.vertices[0].co.z += 0.25
    edited.data.update()
    session.update(bpy.context.evaluated_depsgraph_get(), view)
    finish(session, 0)
    assert session.meshes.conversions == conversions + 1


def test_a_moved_view_repacks_only_the_camera(session, sample_scene, bpy_with_whitted):
    bpy = bpy_with_whitted
    depsgraph = bpy.context.evaluated_depsgraph_get()
    view = camera_view(bpy, sample_scene)
    session.update(depsgraph, view)
    finish(session, 0)
    matrix = np.array(view.view_matrix)
    matrix[0, 3] += 0.3  # the view pans
    moved = type(view)(**{**view.__dict__, "view_matrix": tuple(map(tuple, matrix))})
    session.view_moved(depsgraph, moved)
    image = finish(session)
    assert (session.exports, session.reframes) == (1, 1)
    assert image.generation == session.renderer.generation


def test_a_render_border_leaves_the_rest_of_the_view_transparent(
    session, sample_scene, bpy_with_whitted
):
    bpy = bpy_with_whitted
    view = camera_view(bpy, sample_scene)
    bordered = type(view)(**{**view.__dict__, "border": (40, 30, 50, 20)})
    session.update(bpy.context.evaluated_depsgraph_get(), bordered)
    image = finish(session)
    alpha = image.pixels[..., 3]
    assert np.all(alpha[30:50, 40:90] == 1.0)
    assert alpha.sum() == 50 * 20


def test_an_orthographic_view_of_an_orthographic_camera_is_the_camera(
    sample_scene, bpy_with_whitted
):
    bpy = bpy_with_whitted
    _, export = modules()
    sample_scene.camera.data.type = "ORTHO"
    sample_scene.camera.data.shift_x = 0.1
    depsgraph = bpy.context.evaluated_depsgraph_get()
    view = export.view.camera(camera_view(bpy, sample_scene), depsgraph)
    final = export.camera.convert(sample_scene, depsgraph, export.settings.convert(sample_scene))
    assert view.projection == final.projection == "orthographic"
    np.testing.assert_allclose(view.eye, final.eye, atol=1e-5)
    np.testing.assert_allclose(view.view, final.view, atol=1e-6)
    assert math.isclose(view.ortho_height, final.ortho_height, rel_tol=1e-6)
    np.testing.assert_allclose(view.shift, final.shift, atol=1e-6)
    # outside camera view, Blender's orthographic views also see behind the eye
    free = export.view.camera(camera_view(bpy, sample_scene, "ORTHO", clip_end=40.0), depsgraph)
    offset = np.subtract(final.eye, free.eye)
    np.testing.assert_allclose(offset, np.multiply(final.view, 20.0), atol=1e-4)
    # ... and its rays end clip_end past that eye: half of it beyond the view's centre
    assert (free.clip_start, free.clip_end) == (0.0, 40.0)
    # through the camera, the camera's own Clip Start and End, as a final render's
    assert (view.clip_start, view.clip_end) == (final.clip_start, final.clip_end)


def test_a_perspective_view_clips_at_the_views_clip_start_and_end(sample_scene, bpy_with_whitted):
    """View › Clip Start and End, as Cycles' viewport clips (before, its rays never ended)."""
    bpy = bpy_with_whitted
    _, export = modules()
    depsgraph = bpy.context.evaluated_depsgraph_get()
    through = camera_view(bpy, sample_scene, "PERSP", clip_end=7.5)
    free = export.view.camera(type(through)(**{**through.__dict__, "clip_start": 0.25}), depsgraph)
    assert free.projection == "perspective"
    assert (free.clip_start, free.clip_end) == (0.25, 7.5)


def test_a_scene_error_shows_in_the_view_and_is_not_raised(session, sample_scene, bpy_with_whitted):
    bpy = bpy_with_whitted
    ball = next(o for o in sample_scene.objects if o.type == "MESH")
    ball.scale = (0.0, 1.0, 1.0)
    session.update(bpy.context.evaluated_depsgraph_get(), camera_view(bpy, sample_scene))
    assert session.error is not None and ball.name in session.error
    assert ball.name in session.status()


def test_what_whitted_cannot_honour_shows_in_the_views_status(
    session, sample_scene, bpy_with_whitted
):
    bpy = bpy_with_whitted
    light = next(o for o in sample_scene.objects if o.type == "LIGHT")
    light.data.shadow_soft_size = 0.5  # unused by its CS488 light model
    session.update(bpy.context.evaluated_depsgraph_get(), camera_view(bpy, sample_scene))
    finish(session)
    assert f"light '{light.name}'" in session.status() and "Radius 0.5 m" in session.status()


def test_the_views_status_says_when_f12_traces_more_caustic_photons(session, bpy_with_whitted):
    from tests.blender.test_caustics_in_blender import _mirror_scene

    bpy = bpy_with_whitted
    scene = _mirror_scene(bpy)
    scene.whitted.use_auto_photons = False
    session.update(bpy.context.evaluated_depsgraph_get(), camera_view(bpy, scene))
    finish(session)
    assert "caustics from 50,000 photons here, F12 traces 200,000" in session.status()
    scene.whitted.caustic_photons = 40_000  # within the view's own budget: nothing to say
    session.update(bpy.context.evaluated_depsgraph_get(), camera_view(bpy, scene))
    finish(session)
    assert "F12 traces" not in session.status()
    # Automatic: the view's budget is capped at 50,000; the header says F12 may trace more
    # only where the cap cut it
    scene.whitted.use_auto_photons = True
    session.update(bpy.context.evaluated_depsgraph_get(), camera_view(bpy, scene))
    finish(session)
    budget = session.compiled.caustics.budget
    assert budget is not None and budget.photons <= 50_000
    capped = "F12 traces more (automatic)" in session.status()
    assert capped == (budget.reason == "most"), (budget, session.status())


def test_a_final_render_while_the_viewport_renders_completes_and_both_are_right(
    session, sample_scene, bpy_with_whitted, tmp_path
):
    bpy = bpy_with_whitted
    sample_scene.whitted.shadow_samples = 64  # keep the viewport busy meanwhile
    pixels = sample_grid(160, 120, 6)
    expected = expected_pixels(sample_scene, pixels)
    session.update(bpy.context.evaluated_depsgraph_get(), camera_view(bpy, sample_scene))
    session.renderer.wait_for(session.renderer.generation, 0)
    threads_before = threading.active_count()
    sample_scene.render.filepath = str(tmp_path / "final.png")
    bpy.ops.render.render(write_still=True)
    from PIL import Image

    final = np.asarray(Image.open(tmp_path / "final.png"), float)
    got = np.array([final[py, px, :3] for px, py in pixels])
    np.testing.assert_allclose(got, expected, atol=1.6)
    image = finish(session)
    viewport = np.array([srgb_8bit(image.pixels[py, px, :3]) for px, py in pixels])
    np.testing.assert_allclose(viewport, expected, atol=1.6)
    assert threading.active_count() <= threads_before


def test_closing_the_session_stops_its_render_promptly(session, sample_scene, bpy_with_whitted):
    import time

    bpy = bpy_with_whitted
    sample_scene.whitted.shadow_samples = 4096
    sample_scene.whitted.pixel_samples = 8
    session.update(bpy.context.evaluated_depsgraph_get(), camera_view(bpy, sample_scene))
    session.renderer.wait_for(session.renderer.generation, 3)
    start = time.perf_counter()
    session.close()
    assert time.perf_counter() - start < 2.0
    assert not session.renderer._thread.is_alive()
