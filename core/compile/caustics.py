"""The photon pass: caustic photons traced once per compiled scene (core.kernels.photons)
and gathered into the hashed grid the shading points read (core.kernels.caustics).

Model no more than the scene needs: no photon is traced unless caustics are asked for, a
light is there (a report's, or one in Blender's units that casts shadows and lights diffuse
surfaces), some shape's material reflects (reflective caustics) or refracts (refractive
caustics, which need the "blocked" glass-shadow rule: under "attenuated" shadow rays bring
that light already), and some material has a diffuse part to receive them.

The budget. `RenderSettings.caustic_photons` photons ("auto": as many as the caustics in
the frame need, from a pilot pass of PILOT_PHOTONS, core.compile.photon_budget) are shared
among the rows (light, caster hull) in proportion to the power each row sends into its
hull, measured first with PILOT photons a row, so that every photon carries about the same
power wherever it lands. The radii: each photon's disk holds about k of its fellows at
their density about it (core.kernels.caustics), k the square root of the photons stored
(core.compile.photon_grid), at most REACH of the photons' extent. Memory: 88 bytes a
stored photon (position, direction, power, radius, its bucket), at most twice the budget.
"""

from __future__ import annotations

import time
from typing import NamedTuple

import numpy as np

from ..kernels.caster_hulls import HULL_BOX, HULL_SPHERE
from ..kernels.layout import EMITS_DIFFUSE, EMITS_SHADOW, PackedScene
from ..kernels.options import EMITTER_MESH, EMITTER_SUN_CONE
from ..kernels.photons import REFLECTIVE, REFRACTIVE
from ..model import RenderSettings
from ..model.shader import sends_caustics
from ..vocabulary import SHAPE_SPHERE
from .photon_budget import PILOT_PHOTONS, Budget, automatic_budget
from .photon_grid import hashed_grid, neighbour_distances, radius_levels
from .photon_tracer import PhotonTracer, row_power

PILOT = 256  # photons a row, to share out the budget
MARGIN = 1e-6  # relative: how far outside its shape a caster hull lies
MAX_HULLS = 64
BYTES_PER_PHOTON = 88  # stated in the module's docstring and the settings' limit


class CausticReport(NamedTuple):
    traced: int  # photons traced
    stored: int  # photons stored on diffuse surfaces
    radius: float  # the median photon's disk radius, in scene units
    seconds: float
    budget: Budget | None = None  # the automatic budget's figures; None for a count asked for


def branches_of(settings: RenderSettings) -> int:
    """REFLECTIVE | REFRACTIVE as the settings ask, refractive only under "blocked"."""
    bits = REFLECTIVE if "reflective" in settings.caustics else 0
    if "refractive" in settings.caustics and settings.glass_shadows == "blocked":
        bits |= REFRACTIVE
    return bits


def caster_hulls(packed: PackedScene, branches: int, varying=None) -> np.ndarray:
    """float64 (k, 7): the hull (core.kernels.caster_hulls) of each shape row whose material
    may send light on by the branches asked for (a constant one by its terms; a node
    material varying over the surface where `varying`, bool per material row, says so):
    an analytic sphere's own, else its box, each a little outside the shape (photons must
    never start on its surface, where the first hit could be missed)."""
    mats, geo = packed.materials, packed.geometry
    mirror = mats.reflectivity > 0.0 if branches & REFLECTIVE else np.zeros(len(mats.ior), bool)
    specular = (mirror | (mats.transparency > 0.0)) & (mats.shader_range[:, 0] < 0)
    if varying is not None:
        specular |= varying
    rows = []
    for k in np.flatnonzero(specular[packed.surfaces.shape_material]):
        lo, hi = geo.shape_bounds[k, :3], geo.shape_bounds[k, 3:]
        if not (np.isfinite(lo).all() and np.isfinite(hi).all()):
            continue
        pad = MARGIN * (1.0 + np.abs(np.concatenate([lo, hi])).max())
        if geo.shape_kind[k] == SHAPE_SPHERE:
            world = np.linalg.inv(np.vstack([geo.shape_object_from_world[k], [0, 0, 0, 1.0]]))
            radius = np.linalg.norm(world[:3, :3], axis=0).max()
            rows.append([HULL_SPHERE, *world[:3, 3], radius * (1.0 + MARGIN) + pad, 0.0, 0.0])
        else:
            rows.append([HULL_BOX, *(lo - pad), *(hi + pad)])
    hulls = np.array(rows, float).reshape(-1, 7)
    if len(hulls) > MAX_HULLS:
        # every photon tests every hull, and every light gets a row a hull: past this many,
        # one box round them all (each photon then less likely to meet a caster, none lost)
        boxes = geo.shape_bounds[np.flatnonzero(specular[packed.surfaces.shape_material])]
        boxes = boxes[np.isfinite(boxes).all(axis=1)]
        lo, hi = boxes[:, :3].min(axis=0), boxes[:, 3:].max(axis=0)
        pad = MARGIN * (1.0 + np.abs(np.concatenate([lo, hi])).max())
        hulls = np.array([[HULL_BOX, *(lo - pad), *(hi + pad)]])
    return hulls


def add_caustics(packed: PackedScene, settings: RenderSettings, on_photons=None,
                 should_cancel=None, graphs=()):  # fmt: skip
    """(packed with its lights' photon arrays filled, warnings, CausticReport or None).
    on_photons(done, total) is called after each part of the pass; once should_cancel()
    says True no part starts and the scene gets no photons (the render that follows stops
    too, polling the same). graphs: the material table's rows' node graphs (None for a
    constant row): those varying over the surface that may reflect or refract are casters."""
    branches = branches_of(settings)
    warnings = []
    has_glass = bool((packed.materials.transparency > 0.0).any())
    if "refractive" in settings.caustics and not branches & REFRACTIVE and has_glass:
        warnings.append(
            "refractive caustics need glass shadows blocked (Render Properties > Light Paths "
            '> Glass: Blocked; glass_shadows="blocked"): under Attenuated, shadow rays '
            "pass glass already, so none are traced"
        )
    lights = packed.lights
    flags = lights.emitter_flags
    lit = np.flatnonzero((flags & EMITS_SHADOW != 0) & (flags & EMITS_DIFFUSE != 0))
    # the report's lights, numbered after those (core.kernels.photons)
    reported = len(lights.point_position) + len(lights.area_centre) + len(lights.sun_toward)
    lit = np.concatenate([lit, len(flags) + np.arange(reported)])
    if not branches or settings.caustic_photons == 0 or lit.size == 0:
        return packed, warnings, None
    # node materials varying over the surface that may reflect or refract: casters too
    varying = np.zeros(len(packed.materials.ior), bool)
    for k in np.flatnonzero(packed.materials.shader_range[:, 0] >= 0):
        if k < len(graphs) and graphs[k] is not None:
            varying[k] = sends_caustics(graphs[k], bool(branches & REFLECTIVE),
                                        bool(branches & REFRACTIVE))  # fmt: skip
    casters = caster_hulls(packed, branches, varying)
    receives = packed.materials.transparency < 1.0
    if casters.shape[0] == 0 or not receives.any():
        return packed, warnings, None
    start = time.perf_counter()
    rows = np.array([(light, k, PILOT) for light in lit for k in range(len(casters))], np.int64)
    containing = lights_inside(lights, casters)
    power = row_power(packed, settings, branches, casters, containing, rows)
    if power.sum() <= 0.0:
        return packed, warnings, None
    trace = PhotonTracer(packed, settings, branches, casters, containing, rows, power)
    budget = None
    if settings.caustic_photons == "auto":
        pilot = trace(PILOT_PHOTONS, should_cancel=should_cancel)
        if pilot is None:
            return packed, warnings, None
        budget = automatic_budget(packed.frame, settings, pilot.position, pilot.traced)
    total = budget.photons if budget is not None else settings.caustic_photons
    traced = trace(total, on_photons, should_cancel)
    if traced is None:
        return packed, warnings, None
    if traced.dropped:
        warnings.append(f"caustics: {traced.dropped} photons found no room and were dropped")
    position, direction, power_out = traced.position, traced.direction, traced.power
    if len(position) == 0:
        return packed, warnings, CausticReport(traced.traced, 0, 0.0, 0.0, budget)
    radius = neighbour_distances(position)
    levels = radius_levels(radius)
    order, cells = hashed_grid(position, radius, levels)
    lights = lights._replace(
        photon_position=np.ascontiguousarray(position[order]),
        photon_direction=np.ascontiguousarray(direction[order]),
        photon_power=np.ascontiguousarray(power_out[order]),
        photon_radius=np.ascontiguousarray(radius[order]),
        photon_cells=cells,
        photon_levels=levels,
    )
    seconds = time.perf_counter() - start
    median = float(np.median(radius))
    report = CausticReport(traced.traced, traced.stored, median, seconds, budget)
    return packed._replace(lights=lights), warnings, report


def light_centres(lights) -> np.ndarray:
    """float64 (lights, 3): where each light (numbered as core.kernels.photons numbers them)
    is, NaN for suns (never inside anything): an emissive surface's triangles' mean corner."""
    kinds = lights.emitter_kind
    centres = np.array(lights.emitter_position, float).reshape(-1, 3)
    centres[(kinds >= EMITTER_SUN_CONE) & (kinds != EMITTER_MESH)] = np.nan
    for light in np.flatnonzero(kinds == EMITTER_MESH):
        first, count, _, level = (int(v) for v in lights.emitter_param[light])
        corners = lights.glow_triangles[first : first + count * level**2].reshape(-1, 3)
        centres[light] = corners.mean(axis=0)
    suns = np.full((len(lights.sun_toward), 3), np.nan)
    return np.vstack([centres, lights.point_position.reshape(-1, 3),
                      lights.area_centre.reshape(-1, 3), suns])  # fmt: skip


def lights_inside(lights, casters: np.ndarray) -> np.ndarray:
    """uint8 (lights, hulls): 1 where the light's centre is inside the hull (a lamp in a
    glass globe), whose photons then start at the light (core.kernels.caster_hulls)."""
    centres = light_centres(lights)
    inside = np.zeros((len(centres), len(casters)), np.uint8)
    with np.errstate(invalid="ignore"):  # the suns' NaN: inside nothing
        for k, hull in enumerate(casters):
            if hull[0] == HULL_SPHERE:
                inside[:, k] = np.linalg.norm(centres - hull[1:4], axis=1) < hull[4]
            else:
                inside[:, k] = np.all((centres > hull[1:4]) & (centres < hull[4:7]), axis=1)
    return inside
