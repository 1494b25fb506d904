"""The lights, one table per kind: point, area (a parallelogram) and sun."""

from __future__ import annotations

import numpy as np

from ..kernels.layout import Lights
from ..model import AreaLight, DirectionalLight, PointLight
from .arrays import rows


def pack_lights(lights: list) -> Lights:
    points = [light for light in lights if isinstance(light, PointLight)]
    areas = [light for light in lights if isinstance(light, AreaLight)]
    suns = [light for light in lights if isinstance(light, DirectionalLight)]
    toward = [-np.asarray(sun.direction, float) / np.linalg.norm(sun.direction) for sun in suns]
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
    )
