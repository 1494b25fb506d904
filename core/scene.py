"""The scene model: small dataclasses a person can read, and their validation.

Everything here is plain Python and numpy; nothing is Blender-specific. Exporters (the
Blender add-on, the Lua loader) build these objects; `core.packing` turns them into the flat
arrays the kernels read. Validation lives here so that every front end gets the same clear
`SceneError`, naming the object and the field.

Conventions: world space is z-up like Blender's; colours are linear RGB; distances are in
scene units; angles are in degrees.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from core.errors import SceneError

Vec3 = tuple[float, float, float]

# A transform whose smallest singular value is below this fraction of its largest squashes
# the shape flat: the inverse needed for object-space intersection would be meaningless.
_SINGULAR_RATIO = 1e-12


@dataclass
class Camera:
    """A pinhole camera (the report's eye/view/up/fovy).

    eye   -- position of the centre of projection
    view  -- direction the camera looks along; any non-zero length
    up    -- a direction that appears upwards in the image; must not be parallel to `view`
    fovy  -- vertical field of view in degrees, strictly between 0 and 180
    """

    eye: Vec3 = (0.0, 0.0, 0.0)
    view: Vec3 = (0.0, 0.0, -1.0)
    up: Vec3 = (0.0, 1.0, 0.0)
    fovy: float = 50.0
    name: str = "Camera"

    def validate(self) -> None:
        owner = f"camera '{self.name}'"
        _check_vec3(owner, "eye", self.eye)
        _check_vec3(owner, "view", self.view, nonzero=True)
        _check_vec3(owner, "up", self.up, nonzero=True)
        _check_number(owner, "fovy", self.fovy, "an angle in degrees between 0 and 180")
        if not 0.0 < self.fovy < 180.0:
            raise SceneError(owner, "fovy", f"got {self.fovy}; use an angle between 0 and 180")
        view = np.asarray(self.view, float) / np.linalg.norm(self.view)
        up = np.asarray(self.up, float) / np.linalg.norm(self.up)
        if np.linalg.norm(np.cross(view, up)) < 1e-9:
            raise SceneError(owner, "up", f"{self.up} is parallel to view {self.view}")


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
        _check_vec3(owner, "position", self.position)
        _check_vec3(owner, "intensity", self.intensity, nonnegative=True)
        _check_vec3(owner, "attenuation", self.attenuation, nonnegative=True, nonzero=True)


@dataclass(eq=False)
class Material:
    """The report's Phong material.

    diffuse    -- linear RGB diffuse reflectance kd, each channel >= 0
    specular   -- linear RGB specular reflectance ks, each channel >= 0
    shininess  -- Phong exponent p >= 0 in ks (R.V)^p
    """

    diffuse: Vec3 = (0.8, 0.8, 0.8)
    specular: Vec3 = (0.0, 0.0, 0.0)
    shininess: float = 1.0
    name: str = "Material"

    def validate(self, user: str) -> None:
        owner = f"material '{self.name}' (on {user})"
        _check_vec3(owner, "diffuse", self.diffuse, nonnegative=True)
        _check_vec3(owner, "specular", self.specular, nonnegative=True)
        _check_number(owner, "shininess", self.shininess, "a number >= 0")
        if self.shininess < 0:
            raise SceneError(owner, "shininess", f"got {self.shininess}; use a number >= 0")


def _identity() -> np.ndarray:
    return np.eye(4)


@dataclass(eq=False)
class Sphere:
    """The unit sphere (radius 1, centred on the object origin), like Blender's UV sphere.

    world_from_object -- 4x4 affine matrix placing it in the world: any invertible affine
                         transform, non-uniform scale included (an ellipsoid)
    material          -- its `Material`
    """

    name: str = "Sphere"
    material: Material = field(default_factory=Material)
    world_from_object: np.ndarray = field(default_factory=_identity)

    def validate(self) -> None:
        owner = f"sphere '{self.name}'"
        _check_affine(owner, "world_from_object", self.world_from_object)
        if not isinstance(self.material, Material):
            raise SceneError(
                owner, "material", f"got {type(self.material).__name__}; need a Material"
            )
        self.material.validate(owner)


@dataclass
class Scene:
    """Everything that is rendered.

    camera      -- the `Camera`
    shapes      -- the shapes (so far `Sphere`)
    lights      -- the `PointLight`s
    ambient     -- linear RGB ambient light, added as kd * ambient
    background  -- linear RGB colour of rays that hit nothing
    """

    camera: Camera = field(default_factory=Camera)
    shapes: list = field(default_factory=list)
    lights: list = field(default_factory=list)
    ambient: Vec3 = (0.0, 0.0, 0.0)
    background: Vec3 = (0.0, 0.0, 0.0)

    def validate(self) -> None:
        self.camera.validate()
        for light in self.lights:
            light.validate()
        for shape in self.shapes:
            shape.validate()
        _check_vec3("scene", "ambient", self.ambient, nonnegative=True)
        _check_vec3("scene", "background", self.background, nonnegative=True)


@dataclass
class RenderSettings:
    """How to render: image size, tiling, threads.

    width, height -- image size in pixels, each >= 1
    tile_size     -- edge of the square tiles handed to threads and streamed back, >= 1
    threads       -- worker threads; 0 means one per available core
    region        -- optional (x, y, width, height) in pixels, y counted from the top row:
                     render only this part (a render border); pixels are the same as in a
                     full render
    """

    width: int = 640
    height: int = 480
    tile_size: int = 32
    threads: int = 0
    region: tuple[int, int, int, int] | None = None

    def validate(self) -> None:
        owner = "render settings"
        for name in ("width", "height", "tile_size"):
            value = getattr(self, name)
            if not isinstance(value, (int, np.integer)) or value < 1:
                raise SceneError(owner, name, f"got {value!r}; use a whole number >= 1")
        if not isinstance(self.threads, (int, np.integer)) or self.threads < 0:
            raise SceneError(owner, "threads", f"got {self.threads!r}; use 0 (all cores) or more")
        if self.region is not None:
            x, y, w, h = self.region
            if w < 1 or h < 1 or x < 0 or y < 0 or x + w > self.width or y + h > self.height:
                raise SceneError(
                    owner,
                    "region",
                    f"got {self.region}; it must lie inside the {self.width}x{self.height} image",
                )

    def pixel_region(self) -> tuple[int, int, int, int]:
        return self.region if self.region is not None else (0, 0, self.width, self.height)


def _check_number(owner: str, name: str, value, expected: str) -> None:
    if isinstance(value, bool) or not isinstance(value, (int, float, np.number)):
        raise SceneError(owner, name, f"got {value!r}; use {expected}")
    if not math.isfinite(value):
        raise SceneError(owner, name, f"got {value!r}; use {expected}")


def _check_vec3(owner, name, value, nonnegative=False, nonzero=False) -> None:
    try:
        v = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        raise SceneError(owner, name, f"got {value!r}; use three numbers") from None
    if v.shape != (3,):
        raise SceneError(owner, name, f"got {value!r}; use three numbers")
    if not np.all(np.isfinite(v)):
        raise SceneError(owner, name, f"got {value!r}; all three numbers must be finite")
    if nonnegative and np.any(v < 0):
        raise SceneError(owner, name, f"got {value!r}; each number must be >= 0")
    if nonzero and not np.any(v != 0):
        raise SceneError(owner, name, f"got {value!r}; at least one number must be non-zero")


def _check_affine(owner: str, name: str, matrix) -> None:
    m = np.asarray(matrix, dtype=float)
    if m.shape != (4, 4):
        raise SceneError(owner, name, f"got shape {m.shape}; use a 4x4 matrix")
    if not np.all(np.isfinite(m)):
        raise SceneError(owner, name, "contains NaN or infinity; use finite numbers")
    if not np.allclose(m[3], (0.0, 0.0, 0.0, 1.0)):
        raise SceneError(owner, name, f"bottom row is {m[3]}; an affine matrix ends in 0 0 0 1")
    singular_values = np.linalg.svd(m[:3, :3], compute_uv=False)
    if singular_values[-1] <= _SINGULAR_RATIO * singular_values[0]:
        raise SceneError(
            owner,
            name,
            "is singular (a scale of zero along some axis flattens the shape); "
            "give every axis a non-zero scale",
        )
