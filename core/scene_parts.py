"""Camera, lights, textures and materials: the parts of a scene that are not shapes.

Conventions: world space is z-up like Blender's; colours are linear RGB; distances are in
scene units; angles are in degrees.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np

from .checks import check_number, check_vec3
from .errors import SceneError

Vec3 = tuple[float, float, float]


@dataclass
class Camera:
    """A camera: the report's eye/view/up/fovy pinhole, plus a thin lens for depth of field.

    eye             -- position of the centre of projection (the centre of the lens)
    view            -- direction the camera looks along; any non-zero length
    up              -- a direction that appears upwards in the image; not parallel to `view`
    fovy            -- vertical field of view in degrees, strictly between 0 and 180
    aperture_radius -- radius of the lens; 0 is a pinhole (everything sharp)
    focal_distance  -- distance along `view` of the plane that is in focus, > 0
    shift           -- (x, y) offset of the image on the image plane, in half-widths and
                       half-heights of the image (a view-camera lens shift, as Blender's
                       projection matrix gives it): verticals stay vertical
    """

    eye: Vec3 = (0.0, 0.0, 0.0)
    view: Vec3 = (0.0, 0.0, -1.0)
    up: Vec3 = (0.0, 1.0, 0.0)
    fovy: float = 50.0
    name: str = "Camera"
    aperture_radius: float = 0.0
    focal_distance: float = 10.0
    shift: tuple[float, float] = (0.0, 0.0)

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
        check_number(owner, "aperture_radius", self.aperture_radius, low=0.0)
        check_number(owner, "focal_distance", self.focal_distance, low=0.0, low_open=True)
        if len(self.shift) != 2:
            raise SceneError(owner, "shift", f"got {self.shift!r}; use two numbers (x, y)")
        for value in self.shift:
            check_number(owner, "shift", value)


def _check_attenuation(owner: str, attenuation) -> None:
    check_vec3(owner, "attenuation", attenuation, nonnegative=True, nonzero=True)


@dataclass
class PointLight:
    """A point light with the report's attenuation.

    position     -- where the light is
    intensity    -- linear RGB intensity, each channel >= 0
    attenuation  -- (c0, c1, c2): the light reaching distance d is intensity / (c0 + c1 d + c2 d^2);
                    each >= 0 and not all zero
    """

    position: Vec3 = (0.0, 0.0, 0.0)
    intensity: Vec3 = (1.0, 1.0, 1.0)
    attenuation: Vec3 = (1.0, 0.0, 0.0)
    name: str = "Light"

    def validate(self) -> None:
        owner = f"light '{self.name}'"
        check_vec3(owner, "position", self.position)
        check_vec3(owner, "intensity", self.intensity, nonnegative=True)
        _check_attenuation(owner, self.attenuation)


@dataclass
class DirectionalLight:
    """Parallel light from infinitely far away (the sun): no falloff, sharp shadows.

    direction  -- the direction the light travels, from the light onto the scene; non-zero
    intensity  -- linear RGB irradiance on a surface facing the light, each channel >= 0
    """

    direction: Vec3 = (0.0, 0.0, -1.0)
    intensity: Vec3 = (1.0, 1.0, 1.0)
    name: str = "Sun"

    def validate(self) -> None:
        owner = f"directional light '{self.name}'"
        check_vec3(owner, "direction", self.direction, nonzero=True)
        check_vec3(owner, "intensity", self.intensity, nonnegative=True)


@dataclass
class AreaLight:
    """A rectangular light: the parallelogram centre + s edge_u + t edge_v, s, t in [-1/2, 1/2].

    As in the report it acts as point lights of the full `intensity` spread evenly over the
    rectangle (the shading point sees their average), each with the report's attenuation; it
    lights both sides and is not itself visible. Soft shadows come from sampling it
    (`RenderSettings.shadow_samples`).

    centre       -- the centre of the rectangle
    edge_u       -- one full edge, as a vector (its length is the rectangle's width)
    edge_v       -- the other full edge; not parallel to edge_u
    intensity    -- linear RGB, each channel >= 0
    attenuation  -- (c0, c1, c2) as for `PointLight`
    """

    centre: Vec3 = (0.0, 0.0, 0.0)
    edge_u: Vec3 = (1.0, 0.0, 0.0)
    edge_v: Vec3 = (0.0, 1.0, 0.0)
    intensity: Vec3 = (1.0, 1.0, 1.0)
    attenuation: Vec3 = (1.0, 0.0, 0.0)
    name: str = "Area light"

    def validate(self) -> None:
        owner = f"area light '{self.name}'"
        check_vec3(owner, "centre", self.centre)
        u = check_vec3(owner, "edge_u", self.edge_u, nonzero=True)
        v = check_vec3(owner, "edge_v", self.edge_v, nonzero=True)
        if np.linalg.norm(np.cross(u, v)) <= 1e-12 * np.linalg.norm(u) * np.linalg.norm(v):
            raise SceneError(owner, "edge_v", f"{self.edge_v} is parallel to edge_u {self.edge_u}")
        check_vec3(owner, "intensity", self.intensity, nonnegative=True)
        _check_attenuation(owner, self.attenuation)


@dataclass(eq=False)
class Texture:
    """An image that replaces a material's diffuse colour, looked up bilinearly and repeated.

    path    -- an image file Pillow can read (PNG, JPEG, ...); or None when `pixels` is given
    pixels  -- alternatively an (h, w, 3) or (h, w, 4) float array in [0, 1], row 0 at the top
    srgb    -- whether the values are sRGB-encoded (true of ordinary image files, and Blender's
               colour textures) and so converted to linear; False uses them as they are (the
               report's renderer did)
    """

    path: str | Path | None = None
    pixels: np.ndarray | None = None
    srgb: bool = True
    name: str = "Texture"

    def validate(self, owner: str) -> None:
        if (self.path is None) == (self.pixels is None):
            raise SceneError(owner, "texture", "give either an image file path or pixels")
        if self.pixels is not None:
            p = np.asarray(self.pixels)
            if p.ndim != 3 or p.shape[2] not in (3, 4) or min(p.shape[:2]) < 1:
                raise SceneError(owner, "texture", f"pixels of shape {p.shape}; use (h, w, 3|4)")
            return
        path = Path(self.path)
        if not path.is_file():
            raise SceneError(owner, "texture", f"image file '{path}' does not exist")


@dataclass(eq=False)
class Material:
    """The report's material: Phong, plus mirror reflection, refraction and a texture.

    diffuse       -- linear RGB diffuse reflectance kd, each channel >= 0
    specular      -- linear RGB specular reflectance ks, each channel >= 0
    shininess     -- Phong exponent p >= 0 in ks (R.V)^p
    reflectivity  -- 0..1: weight of the mirror-reflected colour added to the surface colour
    transparency  -- 0..1: fraction of the colour that comes from the dielectric: Fresnel's
                     reflectance F times the reflected colour plus (1 - F) times the refracted
                     colour; the other 1 - transparency is the surface colour plus mirror
    outer_ior     -- index of refraction outside the surface (> 0)
    inner_ior     -- index of refraction inside it (> 0); glass is about 1.5
    texture       -- a `Texture` replacing `diffuse`, or None
    """

    diffuse: Vec3 = (0.8, 0.8, 0.8)
    specular: Vec3 = (0.0, 0.0, 0.0)
    shininess: float = 1.0
    name: str = "Material"
    reflectivity: float = 0.0
    transparency: float = 0.0
    outer_ior: float = 1.0
    inner_ior: float = 1.0
    texture: Texture | None = None

    def validate(self, user: str) -> None:
        owner = f"material '{self.name}' (on {user})"
        check_vec3(owner, "diffuse", self.diffuse, nonnegative=True)
        check_vec3(owner, "specular", self.specular, nonnegative=True)
        check_number(owner, "shininess", self.shininess, low=0.0)
        check_number(owner, "reflectivity", self.reflectivity, low=0.0, high=1.0)
        check_number(owner, "transparency", self.transparency, low=0.0, high=1.0)
        check_number(owner, "outer_ior", self.outer_ior, low=0.0, low_open=True)
        check_number(owner, "inner_ior", self.inner_ior, low=0.0, low_open=True)
        if self.texture is not None:
            if not isinstance(self.texture, Texture):
                raise SceneError(owner, "texture", f"got {self.texture!r}; need a Texture")
            self.texture.validate(owner)
