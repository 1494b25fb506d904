"""The lights, one table per kind of the report's (point, area: a parallelogram, sun), one
table for every light in Blender's units (`core.kernels.emitters` reads it), and the
environment's arrays (`core.compile.environment`)."""

from __future__ import annotations

import math

import numpy as np

from ..kernels.layout import (
    EMITS_DIFFUSE,
    EMITS_SHADOW,
    EMITS_SPECULAR,
    EMITS_SPOT,
    EMITS_SPOT_COSINE,
    EMITS_TRANSMISSION,
    Lights,
)
from ..model import AreaLight, DirectionalLight, PointLight
from ..model.emitters import EMITTERS, PanelLight, SphereLight, SpotLight, SunLight
from ..vocabulary import EMITTER_KINDS
from .arrays import concatenated, rows
from .environment import pack_environment


def pack_lights(lights: list, environment=None, glowing=None) -> Lights:
    """`glowing`: emissive surfaces as lights (core.compile.glowing), after the lights."""
    points = [light for light in lights if isinstance(light, PointLight)]
    areas = [light for light in lights if isinstance(light, AreaLight)]
    suns = [light for light in lights if isinstance(light, DirectionalLight)]
    toward = [-np.asarray(sun.direction, float) / np.linalg.norm(sun.direction) for sun in suns]
    emitters = [_emitter_row(light) for light in lights if isinstance(light, EMITTERS)]
    if glowing is not None:
        emitters += glowing.rows
    return Lights(
        point_position=rows([light.position for light in points]),
        point_intensity=rows([light.intensity for light in points]),
        point_attenuation=rows([light.attenuation for light in points]),
        area_centre=rows([light.centre for light in areas]),
        area_edge_u=rows([light.edge_u for light in areas]),
        area_edge_v=rows([light.edge_v for light in areas]),
        area_intensity=rows([light.intensity for light in areas]),
        area_attenuation=rows([light.attenuation for light in areas]),
        sun_toward=rows(toward),
        sun_intensity=rows([sun.intensity for sun in suns]),
        emitter_kind=np.array([e[0] for e in emitters], np.int32),
        emitter_flags=np.array([e[1] for e in emitters], np.int32),
        emitter_position=rows([e[2] for e in emitters]),
        emitter_frame=np.array([e[3] for e in emitters], float).reshape(-1, 3, 3),
        emitter_param=rows([e[4] for e in emitters], 4),
        emitter_radiance=rows([e[5] for e in emitters]),
        glow_triangles=concatenated(glowing.triangles if glowing else [], (0, 9), np.float64),
        glow_cdf=concatenated(glowing.cdfs if glowing else [], (0, 3), np.float64),
        glow_tint=concatenated(glowing.tints if glowing else [], (0, 3), np.float64),
        **pack_environment(environment),
        **no_photons(),
    )


def no_photons() -> dict:
    """Lights' photon arrays holding none (core.compile.caustics fills them)."""
    return dict(
        photon_position=np.zeros((0, 3)),
        photon_direction=np.zeros((0, 3)),
        photon_power=np.zeros((0, 3)),
        photon_radius=np.zeros(0),
        photon_cells=np.zeros(0, np.int64),
        photon_levels=np.zeros(0),
    )


def _flags(light) -> int:
    return (
        (EMITS_SHADOW if light.cast_shadow else 0)
        | (EMITS_DIFFUSE if light.diffuse else 0)
        | (EMITS_SPECULAR if light.specular else 0)
        | (EMITS_TRANSMISSION if light.transmission else 0)
    )


def _emitter_row(light) -> tuple:
    """(kind, flags, position, frame, param, radiance) of a light in Blender's units; the
    radiance is what core.kernels.emitters and the light's sampling module document."""
    flags = _flags(light)
    frame = np.eye(3)
    param = [0.0, 0.0, 0.0, 0.0]
    if isinstance(light, SunLight):
        half = math.radians(light.angle) / 2.0
        toward = -np.asarray(light.direction, float)
        irradiance = np.asarray(light.irradiance, float) / math.pi
        if light.sampling == "cone":
            kind = EMITTER_KINDS["sun_cone"]
            irradiance = irradiance * 2.0 / (1.0 + math.cos(half))
        else:
            kind = EMITTER_KINDS["sun_disk"]
        # 1 - cos h without cancellation: 2 sin^2(h / 2)
        param[:2] = [2.0 * math.sin(half / 2.0) ** 2, math.tan(half)]
        return kind, flags, toward / np.linalg.norm(toward), frame, param, irradiance
    if isinstance(light, PanelLight):
        u, v = np.asarray(light.edge_u, float), np.asarray(light.edge_v, float)
        normal = np.cross(u, v)
        frame = np.array([u, v, -normal / np.linalg.norm(normal)])
        radiance = np.asarray(light.power, float) / math.pi**2
        kind = EMITTER_KINDS[light.shape]
        return kind, flags, light.centre, frame, param, radiance
    assert isinstance(light, SphereLight)
    kind = EMITTER_KINDS["facing_disk" if light.soft_falloff else "sphere"]
    param[0] = light.radius
    if isinstance(light, SpotLight):
        frame = np.asarray(light.world_to_light, float)
        cos_half = math.cos(math.radians(light.spot_size) / 2.0)
        param[1:3] = [cos_half, (1.0 - cos_half) * light.blend]
        flags |= EMITS_SPOT | (EMITS_SPOT_COSINE if light.cosine_falloff else 0)
    radiance = np.asarray(light.power, float) / (4.0 * math.pi**2)
    return kind, flags, light.position, frame, param, radiance
