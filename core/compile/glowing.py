"""Emissive surfaces as lights: each scene shape whose material emits a constant radiance
(and lets it light the scene: `Material.emission_lights`) becomes a row of the emitter table
(core.kernels.emitters), so that diffuse surfaces get its light by shadow rays as they get a
lamp's, as Cycles' mesh lights give it.

- a mesh: its triangles in world space, picked in proportion to their area
  (core.kernels.light_mesh); radiance L_e / pi in the table
- a sphere under a uniform scale r: a sphere light of radius r (core.kernels.light_sphere),
  whose table radiance r^2 L_e makes it shine with L_e

Either way the light is not seen again by mirror and glass rays (the surface itself is), and
its shadow rays stop just short of the surface they aim at. Other shapes (and emission that
varies over the surface) do not light the scene, and say so.
"""

from __future__ import annotations

import math

import numpy as np

from ..kernels.layout import EMITS_DIFFUSE, EMITS_FROM_SURFACE, EMITS_SHADOW
from ..model.shader import emits
from ..model.shapes import Mesh, Sphere
from ..vocabulary import EMITTER_KINDS

# The most emissive surfaces that light the scene: each adds shadow rays at every shading
# point (Cycles' light tree picks among many; this keeps the brightest)
MAX_GLOWING = 64


class Glowing:
    """Emitter rows (as core.compile.lights makes them) and the triangles they sample."""

    def __init__(self):
        self.rows: list = []
        self.triangles: list = []  # (n, 9) world corners per mesh emitter
        self.cdfs: list = []
        self.count = 0
        self.warnings: list[str] = []


def glowing_shapes(scene_shapes: list, materials, material_of: dict) -> Glowing:
    """The emissive scene shapes as lights; `materials` is the packed table (folded)."""
    out = Glowing()
    candidates = []
    for shape in scene_shapes:
        row = material_of.get(id(shape.material))
        if row is None or not (shape.material.emission_lights and shape.lights_diffuse):
            continue
        if materials.shader_range[row, 0] >= 0:
            if emits(shape.material.surface):
                out.warnings.append(
                    f"{shape.owner}: its material '{shape.material.name}' emits a radiance that "
                    "varies over the surface: seen, but not lighting the scene"
                )
            continue
        radiance = np.asarray(materials.emission[row], float)
        if not np.any(radiance > 0.0):
            continue
        if isinstance(shape, Mesh) or (
            isinstance(shape, Sphere) and _uniform_scale(shape.world_from_object) is not None
        ):
            candidates.append((shape, radiance))
        else:
            out.warnings.append(
                f"{shape.owner}: emits light that lights nothing else (only meshes and "
                "evenly scaled spheres light the scene): tag it as a mesh to light with it"
            )
    if len(candidates) > MAX_GLOWING:
        # Every shading point samples every one: keep the brightest
        candidates.sort(key=lambda c: -_power(*c))
        out.warnings.append(
            f"{len(candidates)} emissive objects would light the scene; the {MAX_GLOWING} "
            "brightest do (each costs shadow rays at every point); set Whitted Material › "
            "Emission Lights to Off on the others"
        )
        candidates = candidates[:MAX_GLOWING]
    for shape, radiance in candidates:
        if isinstance(shape, Mesh):
            _mesh(out, shape, radiance)
        else:
            _sphere(out, shape, radiance)
    return out


def _world_triangles(shape):
    """A mesh shape's triangles in world space, (t, 3, 3), and their areas."""
    m = np.asarray(shape.world_from_object, float)
    vertices = np.asarray(shape.mesh.vertices, float) @ m[:3, :3].T + m[:3, 3]
    corners = vertices[np.asarray(shape.mesh.triangles, np.int64)]
    areas = 0.5 * np.linalg.norm(np.cross(corners[:, 1] - corners[:, 0],
                                          corners[:, 2] - corners[:, 0]), axis=1)  # fmt: skip
    return corners, areas


def _mesh(out: Glowing, shape, radiance) -> None:
    corners, areas = _world_triangles(shape)
    keep = areas > 0.0
    corners, areas = corners[keep], areas[keep]
    if not len(areas):
        return
    total = float(areas.sum())
    cdf = np.cumsum(areas) / total
    cdf[-1] = 1.0
    param = [float(out.count), float(len(areas)), total, 0.0]
    out.triangles.append(corners.reshape(-1, 9))
    out.cdfs.append(cdf)
    out.count += len(areas)
    flags = EMITS_SHADOW | EMITS_DIFFUSE | EMITS_FROM_SURFACE
    out.rows.append((EMITTER_KINDS["mesh"], flags, (0.0, 0.0, 0.0), np.eye(3), param,
                     radiance / math.pi))  # fmt: skip


def _sphere(out: Glowing, shape, radiance) -> None:
    m = np.asarray(shape.world_from_object, float)
    r = _uniform_scale(m)
    flags = EMITS_SHADOW | EMITS_DIFFUSE | EMITS_FROM_SURFACE
    out.rows.append((EMITTER_KINDS["sphere"], flags, tuple(m[:3, 3]), np.eye(3),
                     [r, 0.0, 0.0, 0.0], radiance * r * r))  # fmt: skip


def _power(shape, radiance) -> float:
    """The surface's emitted power, up to a constant: its area times its mean radiance."""
    if isinstance(shape, Mesh):
        area = float(_world_triangles(shape)[1].sum())
    else:
        area = 4.0 * math.pi * _uniform_scale(shape.world_from_object) ** 2
    return float(area * np.mean(radiance))


def _uniform_scale(m) -> float | None:
    """r if the transform's linear part is r times a rotation, else None."""
    linear = np.asarray(m, float)[:3, :3]
    gram = linear.T @ linear
    r2 = float(np.trace(gram) / 3.0)
    if r2 <= 0.0 or np.abs(gram - r2 * np.eye(3)).max() > 1e-9 * r2:
        return None
    return math.sqrt(r2)
