"""The environment: light from infinitely far in every direction, as Blender's World gives it.

A uniform colour, or an equirectangular image (latitude and longitude, Blender's Environment
Texture) times a tint, seen behind everything, in every reflected and refracted ray, and
lighting diffuse surfaces through shadow rays (`RenderSettings.environment_samples` per
shading point, importance-sampled by the image's brightness; occluded as any light).

Directions map onto the image as Blender's equirectangular projection does: a direction d,
first taken through `direction_from_world` (the World's Mapping node), has
u = (pi - atan2(y, x)) / (2 pi) from the left edge and v = 1 - acos(z / |d|) / pi from the
bottom, so the image's centre column faces +X, its left and right edges -X, its top row
straight up; the image repeats past its edges, as Cycles' lookup does.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ..checks import Vec3, check_choice, check_flag, check_light
from ..errors import SceneError
from .materials import Texture

INTERPOLATIONS = ("linear", "closest")


@dataclass(eq=False)
class Environment:
    """colour               -- linear RGB radiance (W / m^2 / sr), or the image's tint
    image                -- an equirectangular `Texture` (linear values, unclamped), or None
    direction_from_world -- 3 x 4 affine rows taking a view direction to the direction the
                            image is looked up with (identity: none)
    interpolation        -- "linear" (bilinear) or "closest" between the image's pixels
    camera, diffuse, glossy, transmission -- which rays see it (Blender's World > Settings >
                            Ray Visibility): camera rays, its light on diffuse surfaces,
                            reflected rays, refracted rays; a ray it is hidden from sees black
    name                 -- what warnings and errors call it (the World's name)
    """

    colour: Vec3 = (0.0, 0.0, 0.0)
    image: Texture | None = None
    direction_from_world: np.ndarray = field(default_factory=lambda: np.eye(3, 4))
    interpolation: str = "linear"
    camera: bool = True
    diffuse: bool = True
    glossy: bool = True
    transmission: bool = True
    name: str = "World"

    def validate(self) -> None:
        owner = f"world '{self.name}'"
        check_light(owner, "colour", self.colour)
        check_choice(owner, "interpolation", self.interpolation, INTERPOLATIONS)
        for switch in ("camera", "diffuse", "glossy", "transmission"):
            check_flag(owner, switch, getattr(self, switch))
        matrix = np.asarray(self.direction_from_world, dtype=float)
        if matrix.shape != (3, 4) or not np.all(np.isfinite(matrix)):
            raise SceneError(owner, "direction_from_world", "needs 3 x 4 finite numbers")
        if self.image is not None:
            if not isinstance(self.image, Texture):
                raise SceneError(owner, "image", f"got {self.image!r}; need a Texture")
            self.image.validate(owner)

    def is_dark(self) -> bool:
        return not np.any(np.asarray(self.colour, float) > 0.0)
