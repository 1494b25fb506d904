"""A `core.Scene` written as a POV-Ray 3.7 scene of the same geometry, for timing against it.

Every shape keeps its exact form and its transform (POV-Ray's `matrix`), so both renderers
trace the same surfaces: spheres, boxes, capped cylinders and cones, tori, CSG trees, and
meshes as `mesh2` with the same triangles, corner normals and UVs. The camera is given as
POV-Ray's direction/right/up vectors computed from the `Camera`, the area light as an
`area_light` with as many samples as Whitted casts, and the settings as POV-Ray's: camera
rays per pixel (`+A0.0 +AM1 +R<n>`), recursion depth (`max_trace_level`), adaptive depth
control off (`adc_bailout` at Whitted's own cut-off), no jitter of the camera samples.

The lighting model is POV-Ray's `finish` with the report's terms: `ambient` (the scene's
ambient times the diffuse colour), `diffuse 1`, `phong` with `phong_size` (Phong's cosine
power of the reflected light, grey), `reflection`. POV-Ray shades an area light once, from its
centre, and only averages the shadow rays; `area_illumination on` makes it shade every sample
as Whitted does. Textures map by UV on meshes (as in Whitted); on analytic shapes POV-Ray's
own UV layout differs from Whitted's, which changes the picture there but not the work.
Transparency (glass) and light falloff other than none are not written: they raise.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np
from PIL import Image

import core

# Whitted stops a ray whose weight can no longer show (core.kernels.integrator.MIN_WEIGHT);
# POV-Ray's adaptive depth control does the same at 1/255 unless told otherwise
ADC_BAILOUT = 1e-6


def vector(v) -> str:
    return "<" + ", ".join(f"{float(x):.9g}" for x in v) + ">"


def matrix(world_from_object: np.ndarray) -> str:
    """POV-Ray's `matrix`: row vectors, so its rows are the columns of our column-vector
    transform, then the translation."""
    m = np.asarray(world_from_object, float)
    values = [*m[:3, 0], *m[:3, 1], *m[:3, 2], *m[:3, 3]]
    return "matrix <" + ", ".join(f"{x:.12g}" for x in values) + ">"


def light_grid(samples: int) -> tuple[int, int]:
    """An nu x nv grid of exactly `samples` points, as square as possible (40 -> 5 x 8)."""
    nu = max(d for d in range(1, int(math.isqrt(samples)) + 1) if samples % d == 0)
    return nu, samples // nu


class PovWriter:
    """Collects the scene's text; textures are written into `folder` as PNG files."""

    def __init__(self, folder: Path):
        self.folder = folder
        self.textures: dict[int, str] = {}
        self.meshes: dict[int, str] = {}
        self.lines: list[str] = []

    def texture_file(self, texture: core.Texture) -> str:
        if id(texture) not in self.textures:
            name = f"texture_{len(self.textures)}.png"
            if texture.pixels is not None:
                pixels = np.clip(np.asarray(texture.pixels, float)[:, :, :3], 0.0, 1.0)
                Image.fromarray(np.round(pixels * 255.0).astype(np.uint8), "RGB").save(
                    self.folder / name
                )
            else:
                Image.open(texture.path).convert("RGB").save(self.folder / name)
            self.textures[id(texture)] = name
        return self.textures[id(texture)]

    def material(self, material: core.Material, ambient, uv: bool) -> str:
        if material.transparency > 0.0:
            raise ValueError(f"material '{material.name}': transparency is not written")
        if material.texture is not None:
            # POV-Ray decodes an 8-bit PNG as sRGB, as Whitted does a texture marked srgb
            gamma = "" if material.texture.srgb else " gamma 1.0"
            mapping = "uv_mapping " if uv else ""
            pigment = (
                f'pigment {{ {mapping}image_map {{ png "{self.texture_file(material.texture)}"'
                f"{gamma} interpolate 2 }} }}"
            )
        else:
            pigment = f"pigment {{ rgb {vector(material.diffuse)} }}"
        phong = float(np.mean(material.specular))
        finish = f"ambient rgb {vector(ambient)} diffuse 1 brilliance 1"
        if phong > 0.0:
            finish += f" phong {phong:.9g} phong_size {material.shininess:.9g}"
        if material.reflectivity > 0.0:
            finish += f" reflection {{ {material.reflectivity:.9g} }}"
        return f"texture {{ {pigment} finish {{ {finish} }} }}"

    def mesh(self, mesh: core.TriangleMesh) -> str:
        """The mesh as a declared mesh2 (once per TriangleMesh, shared like Whitted's)."""
        if id(mesh) in self.meshes:
            return self.meshes[id(mesh)]
        name = f"Mesh_{len(self.meshes)}"
        vertices = np.asarray(mesh.vertices, float)
        triangles = np.asarray(mesh.triangles, np.int64)
        corners = vertices[triangles]
        face_normals = np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0])
        keep = np.linalg.norm(face_normals, axis=1) > 0.0  # Whitted drops zero-area faces
        normals = corner_normals(mesh, face_normals)
        uvs = None
        if mesh.corner_uvs is not None:
            uvs = np.asarray(mesh.corner_uvs, float)
        elif mesh.vertex_uvs is not None:
            uvs = np.asarray(mesh.vertex_uvs, float)[triangles]
        triangles, normals = triangles[keep], normals[keep]
        uvs = uvs[keep] if uvs is not None else None
        count = len(triangles)
        corner_index = np.arange(3 * count).reshape(count, 3)
        parts = [f"#declare {name} = mesh2 {{"]
        parts.append(_block("vertex_vectors", vertices))
        parts.append(_block("normal_vectors", normals.reshape(-1, 3)))
        if uvs is not None:
            parts.append(_block("uv_vectors", uvs.reshape(-1, 2)))
        parts.append(_block("face_indices", triangles))
        parts.append(_block("normal_indices", corner_index))
        if uvs is not None:
            parts.append(_block("uv_indices", corner_index))
        # Meshes inside CSG need an inside test: a ray cast along +z counts crossings
        parts.append("inside_vector <0, 0, 1>\n}")
        self.lines.append("\n".join(parts))
        self.meshes[id(mesh)] = name
        return name

    def shape(self, shape, ambient) -> str:
        """One object (with its transform relative to its parent, if a CSG operand)."""
        place = matrix(shape.world_from_object)
        uv = isinstance(shape, core.Mesh | core.Sphere | core.Box | core.Torus)
        texture = self.material(shape.material, ambient, uv)
        if isinstance(shape, core.Csg):
            operation = {"union": "union", "intersection": "intersection",
                         "difference": "difference"}[shape.operation]  # fmt: skip
            left = self.shape(shape.left, ambient)
            right = self.shape(shape.right, ambient)
            return f"{operation} {{\n{left}\n{right}\n{place}\n}}"
        if isinstance(shape, core.Sphere):
            body = "sphere { <0, 0, 0>, 1"
        elif isinstance(shape, core.Box):
            body = "box { <-1, -1, -1>, <1, 1, 1>"
        elif isinstance(shape, core.Cylinder):
            body = "cylinder { <0, 0, -1>, <0, 0, 1>, 1"
        elif isinstance(shape, core.Cone):
            body = "cone { <0, 0, -1>, 1, <0, 0, 1>, 0"
        elif isinstance(shape, core.Torus):
            # POV-Ray's torus turns about y; a quarter turn about x stands it about z
            body = f"torus {{ {shape.major_radius:.12g}, {shape.minor_radius:.12g} rotate x*90"
        elif isinstance(shape, core.Mesh):
            body = f"object {{ {self.mesh(shape.mesh)}"
        else:
            raise ValueError(f"{shape.owner}: no POV-Ray form for {type(shape).__name__}")
        shadow = "" if shape.casts_shadows else " no_shadow"
        return f"{body} {texture} {place}{shadow} }}"


def corner_normals(mesh: core.TriangleMesh, face_normals: np.ndarray) -> np.ndarray:
    """(t, 3, 3) shading normals per corner, as Whitted shades: the given corner or vertex
    normals on smooth faces (area-weighted vertex normals when none are given), the face
    normal on flat ones."""
    triangles = np.asarray(mesh.triangles, np.int64)
    if mesh.corner_normals is not None:
        smooth_normals = np.asarray(mesh.corner_normals, float)
    else:
        if mesh.vertex_normals is not None:
            per_vertex = np.asarray(mesh.vertex_normals, float)
        else:
            per_vertex = np.zeros((len(mesh.vertices), 3))
            for k in range(3):
                np.add.at(per_vertex, triangles[:, k], face_normals)
        smooth_normals = per_vertex[triangles]
    flat = np.repeat(face_normals[:, None, :], 3, axis=1)
    smooth = np.broadcast_to(np.asarray(mesh.smooth, bool), (len(triangles),))
    normals = np.where(smooth[:, None, None], smooth_normals, flat)
    length = np.linalg.norm(normals, axis=2, keepdims=True)
    return normals / np.where(length > 0.0, length, 1.0)


def _block(name: str, rows: np.ndarray) -> str:
    rows = np.asarray(rows)
    if rows.dtype.kind == "f":
        items = ["<" + ", ".join(f"{x:.9g}" for x in r) + ">" for r in rows]
    else:
        items = ["<" + ", ".join(str(int(x)) for x in r) + ">" for r in rows]
    return f"  {name} {{ {len(rows)},\n    " + ",\n    ".join(items) + "\n  }"


def camera_block(camera: core.Camera, width: int, height: int) -> str:
    """The camera from its definition (`core.Camera`), worked out here rather than taken from
    Whitted's packing, so that the object-mask comparison checks Whitted's camera too."""
    forward = np.asarray(camera.view, float)
    forward /= np.linalg.norm(forward)
    right = np.cross(forward, np.asarray(camera.up, float))
    right /= np.linalg.norm(right)
    up = np.cross(right, forward)
    half_height = math.tan(math.radians(camera.fovy) / 2.0)
    half_width = half_height * width / height
    if camera.aperture_radius > 0.0 or any(camera.shift):
        raise ValueError(f"camera '{camera.name}': depth of field and lens shift are not written")
    # POV-Ray spans the image with `right` (full width) and `up` (full height) at `direction`
    return (
        f"camera {{ perspective location {vector(camera.eye)} direction {vector(forward)} "
        f"right {vector(right * 2.0 * half_width)} up {vector(up * 2.0 * half_height)} }}"
    )


@dataclass(frozen=True)
class AreaSampling:
    """How POV-Ray samples an area light, as its users set it: a `grid` of points (nu, nv),
    `jitter`ed or not, and `adaptive` n (None: off) — POV-Ray then casts (2^n + 1)^2 rays
    first and subdivides the grid only where they disagree (the grid's sides are best
    2^m + 1)."""

    grid: tuple[int, int]
    jitter: bool = True
    adaptive: int | None = None

    def keywords(self) -> str:
        adaptive = f" adaptive {self.adaptive}" if self.adaptive is not None else ""
        return f"{self.grid[0]}, {self.grid[1]}{adaptive}{' jitter' if self.jitter else ''}"


@dataclass(frozen=True)
class Antialiasing:
    """POV-Ray's anti-aliasing options: `method` 1 (a pixel supersampled on a depth x depth
    grid where it differs from its neighbours by more than `threshold`; 0 supersamples every
    pixel) or 2 (corners, subdivided recursively up to `depth` where they differ), or 0
    (one ray a pixel); camera-ray jitter off unless asked for, so each setting draws one
    picture."""

    method: int
    threshold: float = 0.0
    depth: int = 3
    jitter: bool = False

    def options(self) -> list[str]:
        if self.method == 0:
            return ["-A"]
        jitter = "+J" if self.jitter else "-J"
        return [f"+A{float(self.threshold)!r}", f"+AM{self.method}", f"+R{self.depth}", jitter]


def light_block(
    light, shadow_samples: int, area_illumination: bool, area: AreaSampling | None = None
) -> str:
    if not np.allclose(getattr(light, "attenuation", (1.0, 0.0, 0.0)), (1.0, 0.0, 0.0)):
        raise ValueError(f"light '{light.name}': only attenuation (1, 0, 0) is written")
    colour = f"color rgb {vector(light.intensity)}"
    if isinstance(light, core.PointLight):
        return f"light_source {{ {vector(light.position)} {colour} }}"
    if isinstance(light, core.AreaLight):
        area = area or AreaSampling(light_grid(shadow_samples))
        illumination = " area_illumination on" if area_illumination else ""
        return (
            f"light_source {{ {vector(light.centre)} {colour} area_light "
            f"{vector(light.edge_u)}, {vector(light.edge_v)}, {area.keywords()}{illumination} }}"
        )
    if isinstance(light, core.DirectionalLight):
        toward = -np.asarray(light.direction, float)
        return f"light_source {{ {vector(toward * 1e6)} {colour} parallel point_at <0, 0, 0> }}"
    raise ValueError(f"light '{light.name}': no POV-Ray form for {type(light).__name__}")


def write_pov(
    scene: core.Scene,
    settings: core.RenderSettings,
    folder: Path,
    area_illumination: bool = False,
    area: AreaSampling | None = None,
) -> Path:
    """Write `scene.pov` (and its textures) into `folder`; returns its path. Area lights are
    sampled as `area` says, or on a jittered grid of settings.shadow_samples points."""
    folder.mkdir(parents=True, exist_ok=True)
    writer = PovWriter(folder)
    objects = [writer.shape(shape, scene.ambient) for shape in scene.shapes]
    header = [
        "#version 3.7;",
        "global_settings { assumed_gamma 1.0 ambient_light rgb <1, 1, 1> "
        f"max_trace_level {settings.max_depth + 1} adc_bailout {ADC_BAILOUT:.9g} }}",
        f"background {{ rgb {vector(scene.background)} }}",
        camera_block(scene.camera, settings.width, settings.height),
        *(
            light_block(light, settings.shadow_samples, area_illumination, area)
            for light in scene.lights
        ),
    ]
    path = folder / "scene.pov"
    path.write_text("\n".join([*header, *writer.lines, *objects]) + "\n")
    return path


def povray_command(
    pov: Path,
    out: Path,
    settings: core.RenderSettings,
    threads: int,
    antialiasing: Antialiasing | None = None,
    file_format: str = "N8",
) -> list:
    """POV-Ray's command line at Whitted's settings: n x n camera rays on a grid in every
    pixel (threshold 0, no jitter) unless `antialiasing` says otherwise, `threads` render
    threads, no display, the file format given (POV-Ray's +F letter and bits: PNG of 8 bits a
    channel, or "P16", a PPM of 16)."""
    n = settings.pixel_samples
    antialiasing = antialiasing or Antialiasing(method=1 if n > 1 else 0, depth=n)
    return [
        "povray", f"+I{pov.name}", f"+O{out}", f"+F{file_format}", f"+W{settings.width}",
        f"+H{settings.height}", f"+WT{threads}", *antialiasing.options(), "-D", "-P", "+V",
        "File_Gamma=1.0",
    ]  # fmt: skip
