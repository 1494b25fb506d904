"""The camera: the report's pinhole, or an orthographic one, plus a thin lens for depth of
field."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..checks import Vec3, check_choice, check_number, check_vec3
from ..errors import SceneError
from ..vocabulary import PROJECTIONS

# Blender's Blades field stops at 100; more sides than that are a disk to the eye
MAX_BLADES = 100


@dataclass
class Camera:
    """A camera: the report's eye/view/up/fovy pinhole, plus a thin lens for depth of field.

    eye             -- position of the centre of projection (the centre of the lens)
    view            -- direction the camera looks along; any non-zero length
    up              -- a direction that appears upwards in the image; not parallel to `view`
    projection      -- "perspective" (rays from the eye) or "orthographic" (rays parallel to
                       `view`, from the plane through the eye square to it)
    fovy            -- vertical field of view in degrees, strictly between 0 and 180
                       (perspective)
    ortho_height    -- height of the image in scene units, > 0 (orthographic)
    aperture_radius -- radius of the lens; 0 is a pinhole (everything sharp)
    aperture_blades -- the aperture's shape: 0 (or 1, 2) a disk; n >= 3 a regular n-gon whose
                       corners lie on the circle of aperture_radius (polygonal bokeh)
    aperture_rotation -- the polygon's turn about the view axis, in radians
    aperture_ratio  -- the aperture's width is divided by this (anamorphic bokeh): below 1
                       out-of-focus highlights stretch sideways, above 1 upwards; 1 is round
    focal_distance  -- distance along `view` of the plane that is in focus, > 0
    shift           -- (x, y) offset of the image on the image plane, in half-widths and
                       half-heights of the image (a view-camera lens shift, as Blender's
                       projection matrix gives it): verticals stay vertical
    clip_start      -- camera rays start this far along the view direction, >= 0 (Blender's
                       Clip Start, as Cycles clips): nearer surfaces are not seen, and Light
                       Path's Ray Length of a camera ray counts from there
    clip_end        -- camera rays end this far along the view direction, > 0 (Blender's
                       Clip End, as Cycles clips; inf: they never end): what lies beyond is
                       not seen, the World is (all of it, at or before clip_start)
    """

    eye: Vec3 = (0.0, 0.0, 0.0)
    view: Vec3 = (0.0, 0.0, -1.0)
    up: Vec3 = (0.0, 1.0, 0.0)
    fovy: float = 50.0
    name: str = "Camera"
    aperture_radius: float = 0.0
    aperture_blades: int = 0
    aperture_rotation: float = 0.0
    aperture_ratio: float = 1.0
    focal_distance: float = 10.0
    shift: tuple[float, float] = (0.0, 0.0)
    projection: str = "perspective"
    ortho_height: float = 2.0
    clip_start: float = 0.0
    clip_end: float = math.inf

    def validate(self) -> None:
        owner = f"camera '{self.name}'"
        check_vec3(owner, "eye", self.eye)
        view = check_vec3(owner, "view", self.view, nonzero=True)
        up = check_vec3(owner, "up", self.up, nonzero=True)
        check_number(owner, "fovy", self.fovy, low=0.0, high=180.0, low_open=True)
        if self.fovy == 180.0:
            raise SceneError(owner, "fovy", "got 180.0; use an angle between 0 and 180")
        view, up = view / np.linalg.norm(view), up / np.linalg.norm(up)
        if np.linalg.norm(np.cross(view, up)) < 1e-9:
            raise SceneError(owner, "up", f"{self.up} is parallel to view {self.view}")
        check_choice(owner, "projection", self.projection, tuple(PROJECTIONS))
        check_number(owner, "ortho_height", self.ortho_height, low=0.0, low_open=True)
        check_number(owner, "aperture_radius", self.aperture_radius, low=0.0)
        check_number(owner, "aperture_blades", self.aperture_blades, low=0, high=MAX_BLADES)
        if self.aperture_blades != int(self.aperture_blades):
            raise SceneError(
                owner, "aperture_blades", f"got {self.aperture_blades!r}; use a whole number"
            )
        check_number(owner, "aperture_rotation", self.aperture_rotation)
        check_number(owner, "aperture_ratio", self.aperture_ratio, low=0.0, low_open=True)
        check_number(owner, "focal_distance", self.focal_distance, low=0.0, low_open=True)
        check_number(owner, "clip_start", self.clip_start, low=0.0)
        if self.clip_end != math.inf:
            check_number(owner, "clip_end", self.clip_end, low=0.0, low_open=True)
        if len(self.shift) != 2:
            raise SceneError(owner, "shift", f"got {self.shift!r}; use two numbers (x, y)")
        for value in self.shift:
            check_number(owner, "shift", value)
