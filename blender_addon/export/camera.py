"""The active camera -> core.Camera: eye, view (-Z), up (+Y) from its world matrix; the
vertical field of view (perspective) or the view's height (orthographic) from Blender's own
projection matrix, so sensor size, sensor fit, lens and orthographic scale all count; lens
shift; depth of field as Cycles reads it."""

from __future__ import annotations

import math

from .. import core


def convert(scene, depsgraph, settings: core.RenderSettings) -> core.Camera:
    if scene.camera is None:
        raise core.SceneError(
            f"scene '{scene.name}'",
            "camera",
            "there is no active camera; add a camera and set it in Scene Properties > Camera",
        )
    camera = scene.camera.evaluated_get(depsgraph)
    owner = f"camera '{camera.name}'"
    if camera.type != "CAMERA":
        raise core.SceneError(owner, "type", f"is a {camera.type} object; use a camera object")
    if camera.data.type not in ("PERSP", "ORTHO"):
        raise core.SceneError(
            owner,
            "lens type",
            f"is {camera.data.type}; Whitted renders perspective and orthographic cameras: "
            "set Camera Properties > Lens > Type to Perspective or Orthographic",
        )
    _check_lens(camera.data, owner)
    projection = camera.calc_matrix_camera(
        depsgraph,
        x=settings.width,
        y=settings.height,
        scale_x=scene.render.pixel_aspect_x,
        scale_y=scene.render.pixel_aspect_y,
    )
    terms = [value for row in projection for value in row]
    if not all(math.isfinite(value) for value in terms) or projection[1][1] == 0.0:
        raise core.SceneError(
            owner,
            "Camera Properties > Lens",
            "gives Blender no usable projection (a term is infinite or zero); set the lens, "
            "sensor and shift to values a real camera has",
        )
    rotation = camera.matrix_world.to_3x3().normalized()
    eye, view = camera.matrix_world.translation, -rotation.col[2]
    # Clip Start and End: camera rays start and end there, as in Cycles
    clipping = {"clip_start": camera.data.clip_start, "clip_end": camera.data.clip_end}
    lens = {**depth_of_field(scene, camera, eye, view), **clipping}
    return from_projection(projection, eye, view, rotation.col[1], camera.name, lens,
                           orthographic=camera.data.type == "ORTHO")  # fmt: skip


# The largest lens shift read, in sensor widths (Blender's panel offers -2 to 2): past it a
# picture is of a sliver of the view a million widths away
MAX_SHIFT = 100.0
MIN_FSTOP = 1e-5  # Cycles' floor on Depth of Field > F-Stop


def _check_lens(data, owner: str) -> None:
    """The lens settings Blender's properties allow but no projection can use (a zero
    orthographic scale divides by zero), refused in the panel's terms."""
    if data.type == "ORTHO" and not data.ortho_scale > 0.0:
        raise core.SceneError(
            owner,
            "Camera Properties > Lens > Orthographic Scale",
            f"is {data.ortho_scale:g}; give the view's size, above 0",
        )
    for axis in ("x", "y"):
        shift = getattr(data, f"shift_{axis}")
        if not abs(shift) <= MAX_SHIFT:
            raise core.SceneError(
                owner,
                f"Camera Properties > Lens > Shift {axis.upper()}",
                f"is {shift:g}; give a shift from -{MAX_SHIFT:g} to {MAX_SHIFT:g} sensor widths",
            )


def from_projection(
    projection, eye, view, up, name: str, lens: dict, orthographic: bool
) -> core.Camera:
    """A core.Camera from Blender's projection matrix (a camera's `calc_matrix_camera`, a 3D
    view's `window_matrix`), the eye and axes it looks from, and its `depth_of_field`."""
    common = dict(eye=tuple(eye), view=tuple(view), up=tuple(up), name=name, **lens)
    if orthographic:
        # Blender's orthographic projection: 2 / height of the view in its [1][1] term, and
        # the lens shift, in half-widths and half-heights, in the translation column
        return core.Camera(
            projection="orthographic",
            ortho_height=2.0 / projection[1][1],
            shift=(-float(projection[0][3]), -float(projection[1][3])),
            **common,
        )
    return core.Camera(
        fovy=math.degrees(2.0 * math.atan(1.0 / projection[1][1])),
        # The off-axis terms of Blender's projection: the lens shift, in half-widths/heights
        shift=(float(projection[0][2]), float(projection[1][2])),
        **common,
    )


PINHOLE = {"aperture_radius": 0.0, "focal_distance": 10.0}


def depth_of_field(scene, camera, eye, view) -> dict:
    """core.Camera's lens fields from Blender's own camera depth of field, as Cycles reads
    it: radius = focal length / (2 f-stop), in scene units; the focus object's distance along
    the view, else the focus distance; the aperture's Blades, Rotation and Ratio. A pinhole
    when depth of field is off."""
    dof = camera.data.dof
    if not dof.use_dof:
        return dict(PINHOLE)
    focus = dof.focus_distance
    if dof.focus_object is not None:
        focus = float((dof.focus_object.matrix_world.translation - eye).dot(view))
    if focus <= 0.0:
        raise core.SceneError(
            f"camera '{camera.name}'",
            "depth of field focus",
            f"is {focus:.4g} in front of the camera; put the focus object in front of it or "
            "set a positive Focus Distance",
        )
    # As Cycles reads it: an F-Stop of 0 (which Blender's field allows) as 1e-5, the widest
    radius = camera.data.lens * 1e-3 / (2.0 * max(dof.aperture_fstop, MIN_FSTOP))
    return {
        "aperture_radius": radius / scene.unit_settings.scale_length,
        "focal_distance": focus,
        "aperture_blades": int(dof.aperture_blades),
        "aperture_rotation": float(dof.aperture_rotation),
        "aperture_ratio": float(dof.aperture_ratio),
    }
