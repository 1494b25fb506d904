"""A 3D view in Rendered shading -> core.Camera and the settings of its render.

`View` is everything the viewport's picture depends on besides the scene: the region's size,
its view and projection matrices, its kind of view (perspective, orthographic, or through the
scene camera) and its render border. Two equal `View`s give the same picture, which is how the
viewport knows that only the view moved (orbit, zoom, pan, a resized area) and packs only the
camera again.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np
from mathutils import Vector

from .. import core
from .camera import PINHOLE, depth_of_field, from_projection

Matrix4 = tuple[tuple[float, ...], ...]


@dataclass(frozen=True)
class View:
    width: int  # region pixels
    height: int
    view_matrix: Matrix4  # world -> view, as RegionView3D.view_matrix
    window_matrix: Matrix4  # view -> clip, as RegionView3D.window_matrix
    perspective: str  # RegionView3D.view_perspective: "PERSP", "ORTHO" or "CAMERA"
    clip_end: float  # SpaceView3D.clip_end: orthographic views see half of it behind the eye
    border: tuple[int, int, int, int] | None  # (x, y, width, height), y from the region's top
    clip_start: float = 0.0  # SpaceView3D.clip_start (a perspective view's)


def read_view(context) -> View:
    """The View of `context`'s 3D view region (view_draw's context)."""
    region, view3d, space = context.region, context.region_data, context.space_data
    width, height = region.width, region.height
    return View(
        width=width,
        height=height,
        view_matrix=_rows(view3d.view_matrix),
        window_matrix=_rows(view3d.window_matrix),
        perspective=view3d.view_perspective,
        clip_end=float(space.clip_end),
        border=_border(context, width, height),
        clip_start=float(space.clip_start),
    )


def camera(view: View, depsgraph) -> core.Camera:
    """The view as a camera: eye and axes from the inverse view matrix; the field of view (or
    the view's height) and the off-centre shift from the projection matrix, read as
    export.camera reads a camera's. Through the scene camera, its depth of field and Clip
    Start and End too; otherwise the View's Clip Start and End, as Cycles' viewport clips
    (an orthographic view: clip_end across, half of it behind the view's centre)."""
    world_from_view = np.linalg.inv(np.array(view.view_matrix, float))
    projection = view.window_matrix
    axes = world_from_view[:3, :3] / np.linalg.norm(world_from_view[:3, :3], axis=0)
    eye, forward, up = world_from_view[:3, 3], -axes[:, 2], axes[:, 1]
    orthographic = projection[3][3] == 1.0
    lens = {**PINHOLE, "clip_start": 0.0 if orthographic else view.clip_start,
            "clip_end": view.clip_end}  # fmt: skip
    scene_camera = depsgraph.scene.camera
    if view.perspective == "CAMERA" and scene_camera is not None:
        evaluated = scene_camera.evaluated_get(depsgraph)
        if evaluated.type == "CAMERA":
            lens = depth_of_field(
                depsgraph.scene, evaluated, Vector(tuple(eye)), Vector(tuple(forward))
            )
            lens["clip_start"] = evaluated.data.clip_start
            lens["clip_end"] = evaluated.data.clip_end
    if orthographic and view.perspective != "CAMERA":
        # Blender's orthographic views clip half the clip distance behind the eye; rays start
        # on the image plane, so it moves back that far (the picture stays put) and they end
        # clip_end beyond it
        eye = eye - forward * (view.clip_end / 2.0)
    return from_projection(projection, eye, forward, up, "3D Viewport", lens, orthographic)


# The viewport traces at most this many caustic photons (a tenth of a second's pass on the
# development machine), so that a change shows at once; F12 traces the scene's budget
VIEWPORT_PHOTONS = 50_000


def settings(render: core.RenderSettings, view: View) -> core.RenderSettings:
    """The scene's Whitted settings (bounces, samples) at the region's size and border,
    with at most VIEWPORT_PHOTONS caustic photons (the automatic budget's cap)."""
    photons = render.caustic_photons
    if photons != "auto":
        photons = min(photons, VIEWPORT_PHOTONS)
    return replace(render, width=view.width, height=view.height, region=view.border,
                   caustic_photons=photons, caustic_photons_max=VIEWPORT_PHOTONS)  # fmt: skip


def _border(context, width: int, height: int):
    """The render border as Blender draws it in this view: the view's own (Ctrl+B) outside
    camera view, the scene's (Output > Format > Render Region) inside the camera frame in
    camera view; in region pixels, y from the top, truncated as export.settings truncates."""
    view3d, space, scene = context.region_data, context.space_data, context.scene
    if view3d.view_perspective == "CAMERA":
        render = scene.render
        if not render.use_border or scene.camera is None:
            return None
        frame = _camera_frame(context, scene.camera)
        if frame is None:
            return None
        left, bottom, right, top = frame
        x_min = left + render.border_min_x * (right - left)
        x_max = left + render.border_max_x * (right - left)
        y_min = bottom + render.border_min_y * (top - bottom)
        y_max = bottom + render.border_max_y * (top - bottom)
    else:
        if not space.use_render_border:
            return None
        x_min, x_max = space.render_border_min_x * width, space.render_border_max_x * width
        y_min, y_max = space.render_border_min_y * height, space.render_border_max_y * height
    return border_pixels((x_min, y_min, x_max, y_max), width, height)


def border_pixels(corners, width: int, height: int):
    """(x_min, y_min, x_max, y_max) in region pixels, y from the bottom, clipped to the
    region -> (x, y, width, height) with y from the top; None when nothing is left."""
    x_min, y_min, x_max, y_max = (int(max(0.0, c)) for c in corners)
    x_max, y_max = min(x_max, width), min(y_max, height)
    if x_max <= x_min or y_max <= y_min:
        return None
    return (x_min, height - y_max, x_max - x_min, y_max - y_min)


def _camera_frame(context, camera_object):
    """The scene camera's frame in region pixels (left, bottom, right, top): its view frame's
    corners through the region's projection."""
    region, view3d = context.region, context.region_data
    corners = camera_object.data.view_frame(scene=context.scene)
    clip_from_world = np.array(view3d.perspective_matrix, float)
    world_from_camera = np.array(camera_object.matrix_world, float)
    xs, ys = [], []
    for corner in corners:
        point = clip_from_world @ world_from_camera @ np.array([*corner, 1.0])
        if point[3] <= 0.0:
            return None
        xs.append((point[0] / point[3] + 1.0) * 0.5 * region.width)
        ys.append((point[1] / point[3] + 1.0) * 0.5 * region.height)
    return min(xs), min(ys), max(xs), max(ys)


def _rows(matrix) -> Matrix4:
    return tuple(tuple(float(v) for v in row) for row in matrix)
