"""Emissive surfaces as lights: each scene shape whose material emits a constant radiance
(and lets it light the scene: `Material.emission_lights`) becomes a row of the emitter table
(core.kernels.emitters), so that diffuse surfaces get its light by shadow rays as they get a
lamp's, as Cycles' mesh lights give it.

- a mesh: its triangles in world space, picked in proportion to their area
  (core.kernels.light_mesh); radiance L_e / pi in the table
- a sphere under a uniform scale r: a sphere light of radius r (core.kernels.light_sphere),
  whose table radiance r^2 L_e makes it shine with L_e

Either way the light is not seen again by mirror and glass rays (the surface itself is), and
its shadow rays stop just short of the surface they aim at. A mesh whose emission varies
over the surface (a texture in Emission Color) is cut into sub-triangles of their own mean
emission (core.kernels.glow_bake), sampled in proportion to area times emission, each
shining its own colour. Other shapes do not light the scene, and say so.
"""

from __future__ import annotations

import math

import numpy as np

from ..kernels.glow_bake import bake_glow
from ..kernels.layout import EMITS_DIFFUSE, EMITS_FROM_SURFACE, EMITS_SHADOW
from ..kernels.light_mesh import ROW_SHARES, SUB_SHARES, TRIANGLE_SHARES
from ..kernels.shader_program import LOBE_COUNT, SHADER_STACK
from ..model.shader import emits
from ..model.shapes import Mesh, Sphere
from ..vocabulary import EMITTER_KINDS

# The most emissive surfaces that light the scene: each adds shadow rays at every shading
# point (Cycles' light tree picks among many; this keeps the brightest)
MAX_GLOWING = 64
# A varying emitter's sub-triangles (core.kernels.glow_bake): each triangle cut into
# level x level, level as large as keeps the mesh within this many, and at most MAX_LEVEL
# (a quad's 2 triangles: 8192 sub-triangles, 32 768 runs of its program)
SUB_TRIANGLES = 1 << 16
MAX_LEVEL = 64
# ... and all varying emitters within this many together (120 bytes each)
ALL_SUB_TRIANGLES = 1 << 20


class Glowing:
    """Emitter rows (as core.compile.lights makes them) and the triangles they sample."""

    def __init__(self):
        self.rows: list = []
        self.triangles: list = []  # (n, 9) world corners per mesh emitter
        self.cdfs: list = []
        self.tints: list = []  # (n, 3) each triangle's colour against the row's radiance
        self.count = 0
        self.warnings: list[str] = []


def glowing_shapes(scene_shapes: list, packed, material_of: dict) -> Glowing:
    """The emissive scene shapes (rows 0.. of `packed`, a kernel-ready scene whose materials
    are folded) as lights."""
    out = Glowing()
    materials = packed.materials
    candidates = []
    varying = sum(isinstance(s, Mesh) and _varies(s, materials, material_of) for s in scene_shapes)
    budget = max(1, min(SUB_TRIANGLES, ALL_SUB_TRIANGLES // max(varying, 1)))
    for index, shape in enumerate(scene_shapes):
        row = material_of.get(id(shape.material))
        if row is None or not (shape.material.emission_lights and shape.lights_diffuse):
            continue
        if materials.shader_range[row, 0] >= 0:
            if not emits(shape.material.surface):
                continue
            if isinstance(shape, Mesh):
                baked = _baked(packed, index, row, shape, budget)
                if baked is not None:
                    candidates.append((shape, baked))
            else:
                out.warnings.append(
                    f"{shape.owner}: its material '{shape.material.name}' emits a radiance that "
                    "varies over the surface: seen, but not lighting the scene (only meshes "
                    "light with such emission): tag it as a mesh to light with it"
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
        if isinstance(radiance, Baked):
            _varying_mesh(out, radiance)
        elif isinstance(shape, Mesh):
            _mesh(out, shape, radiance)
        else:
            _sphere(out, shape, radiance)
    return out


def _varies(shape, materials, material_of: dict) -> bool:
    """Whether the shape's material may emit, varying over the surface, and light."""
    row = material_of.get(id(shape.material))
    material = shape.material
    return (
        row is not None
        and material.emission_lights
        and shape.lights_diffuse
        and materials.shader_range[row, 0] >= 0
        and emits(material.surface)
    )


class Baked:
    """A varying emitter's sub-triangles (core.kernels.glow_bake), level^2 a triangle in its
    grid's order: world corners (n, 9), areas and emitted radiance (n, 3)."""

    def __init__(self, corners, areas, radiance, level: int):
        self.corners, self.areas, self.radiance, self.level = corners, areas, radiance, level
        # the scalar each is sampled by: its radiance's mean over RGB
        self.strength = radiance.mean(axis=1)
        self.power = float((areas * self.strength).sum())


def _baked(packed, index: int, material: int, shape, budget: int) -> Baked | None:
    """Mesh shape row `index`'s sub-triangles of material row `material`, at most about
    `budget` of them; None if none emits."""
    count = max(len(shape.mesh.triangles), 1)
    level = int(max(1, min(MAX_LEVEL, math.isqrt(max(budget // count, 1)))))
    out = np.zeros((count * level * level, 12))
    matrix = np.ascontiguousarray(np.asarray(shape.world_from_object, float))
    scratch = np.zeros(SHADER_STACK), np.zeros(LOBE_COUNT)
    written = bake_glow(packed.geometry, packed.surfaces, packed.materials, matrix, index,
                        material, level, out, *scratch)  # fmt: skip
    out = out[:written]
    radiance = np.where(np.isfinite(out[:, 9:12]), np.maximum(out[:, 9:12], 0.0), 0.0)
    corners = np.ascontiguousarray(out[:, :9])
    baked = Baked(corners, _areas(corners.reshape(-1, 3, 3)), radiance, level)
    return baked if baked.power > 0.0 else None


def _varying_mesh(out: Glowing, baked: Baked) -> None:
    """Sub-triangles picked in proportion to area times strength; the row's radiance 1/pi
    and each sub-triangle's tint its radiance over its strength, so that a sample carries
    its own radiance (core.kernels.light_mesh)."""
    level = baked.level
    shares = (baked.areas * baked.strength).reshape(-1, level * level)
    strength = np.where(baked.strength > 0.0, baked.strength, 1.0)
    _add_mesh_light(out, baked.corners, shares, level, baked.radiance / strength[:, None],
                    np.full(3, 1.0 / math.pi))  # fmt: skip


def _running(shares: np.ndarray) -> np.ndarray:
    """Running shares along the last axis, ending at exactly 1 (even where all are 0: then
    in equal steps, though nothing picks them)."""
    totals = shares.sum(axis=-1, keepdims=True)
    even = np.broadcast_to(np.arange(1, shares.shape[-1] + 1) / shares.shape[-1], shares.shape)
    with np.errstate(invalid="ignore", divide="ignore"):
        cdf = np.where(totals > 0.0, np.cumsum(shares, axis=-1) / totals, even)
    cdf[..., -1] = 1.0
    return cdf


def _add_mesh_light(out: Glowing, corners, shares, level: int, tints, radiance) -> None:
    """An emitter row over triangles each cut into level^2 sub-triangles (`shares`: (t,
    level^2) their areas times strengths, in core.kernels.glow_bake's order): the three
    columns of running shares core.kernels.light_mesh picks by."""
    count, cuts = shares.shape
    row_of = np.repeat(np.arange(level), 2 * (level - np.arange(level)) - 1)
    in_rows = np.zeros((count, level))
    for r in range(level):
        in_rows[:, r] = shares[:, row_of == r].sum(axis=1)
    cdf = np.ones((count * cuts, 3))
    # each sub-triangle within its row, each row within its triangle, each triangle
    cdf[:, SUB_SHARES] = np.concatenate(
        [_running(shares[:, row_of == r]) for r in range(level)], axis=1
    ).ravel()
    cdf[: count * level, ROW_SHARES] = _running(in_rows).ravel()
    cdf[:count, TRIANGLE_SHARES] = _running(shares.sum(axis=1))
    param = [float(out.count), float(count), float(shares.sum()), float(level)]
    out.triangles.append(corners.reshape(-1, 9))
    out.cdfs.append(cdf)
    out.tints.append(tints)
    out.count += count * cuts
    flags = EMITS_SHADOW | EMITS_DIFFUSE | EMITS_FROM_SURFACE
    out.rows.append((EMITTER_KINDS["mesh"], flags, (0.0, 0.0, 0.0), np.eye(3), param,
                     radiance))  # fmt: skip


def _areas(corners) -> np.ndarray:
    """Areas of triangles (t, 3, 3)."""
    return 0.5 * np.linalg.norm(np.cross(corners[:, 1] - corners[:, 0],
                                         corners[:, 2] - corners[:, 0]), axis=1)  # fmt: skip


def _world_triangles(shape):
    """A mesh shape's triangles in world space, (t, 3, 3), and their areas."""
    m = np.asarray(shape.world_from_object, float)
    vertices = np.asarray(shape.mesh.vertices, float) @ m[:3, :3].T + m[:3, 3]
    corners = vertices[np.asarray(shape.mesh.triangles, np.int64)]
    return corners, _areas(corners)


def _mesh(out: Glowing, shape, radiance) -> None:
    corners, areas = _world_triangles(shape)
    keep = areas > 0.0
    corners, areas = corners[keep], areas[keep]
    if len(areas):
        _add_mesh_light(out, corners, areas[:, None], 1, np.ones((len(areas), 3)),
                        radiance / math.pi)  # fmt: skip


def _sphere(out: Glowing, shape, radiance) -> None:
    m = np.asarray(shape.world_from_object, float)
    r = _uniform_scale(m)
    flags = EMITS_SHADOW | EMITS_DIFFUSE | EMITS_FROM_SURFACE
    out.rows.append((EMITTER_KINDS["sphere"], flags, tuple(m[:3, 3]), np.eye(3),
                     [r, 0.0, 0.0, 0.0], radiance * r * r))  # fmt: skip


def _power(shape, radiance) -> float:
    """The surface's emitted power, up to a constant: its area times its mean radiance."""
    if isinstance(radiance, Baked):
        return radiance.power
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
