"""The light a surface point reflects toward the viewer, from every kind of light a scene
may hold, each a feature of its own (core.kernels.features) that a kernel variant
includes or leaves out:

- the report's point lights and area lights and the ambient term (always);
- Blender's lights, in Blender's units (`emitters`);
- the World's light (`environment`);
- shadow rays that crossed surfaces whose share of light varies over them, answered by
  their shader programs and the lights summed once more (`varying_shadows`);
- light brought by mirrors and glass, gathered from the caustic photons (`caustics`).
"""

import math

from ..jit.decorators import inlined_kernel
from .caustics import caustic_irradiance
from .emitters import emitted_colour
from .environment import environment_light
from .features import WITH_CAUSTICS, WITH_EMITTERS, WITH_ENVIRONMENT, WITH_VARYING_SHADOWS
from .layout import ENVIRONMENT_NONE
from .options import OPTION_ENVIRONMENT, OPTION_ROUGH_DIFFUSE
from .pass_record import TERM_ROW_LIT, TERM_ROW_UNSHADOWED
from .rough_diffuse import rough_albedo
from .shading import local_colour
from .shadow_crossing import answer_crossings
from .shadow_log import begin_point
from .vec import add, dot, mul, scale


@inlined_kernel
def light_at_point(frame, lights, geo, surf, mats, ws, point, phong, p, n_geometric, key,
                   event, splitting, refraction_passes):  # fmt: skip
    """The colour the `Phong` terms reflect at the `ShadingPoint` (its origin lifted off the
    surface at p, whose geometric normal faces the viewer). With `splitting` the pass
    terms (ws.stacks.terms) get the light falling on the point."""
    stacks = ws.stacks
    begin_point(stacks.shadow_state)
    while True:
        local = local_colour(frame, lights, geo, stacks, point, phong, key, event, splitting)
        if WITH_EMITTERS and lights.emitter_kind.shape[0] > 0:
            emitted = emitted_colour(
                frame, lights, geo, stacks, point, phong, key, event, splitting
            )
            local = add(local, emitted)
        if WITH_ENVIRONMENT and frame.options[OPTION_ENVIRONMENT] != ENVIRONMENT_NONE:
            sky = environment_light(
                frame,
                lights,
                geo,
                stacks,
                point,
                phong.kd,
                phong.diffuse_roughness,
                key,
                event,
                splitting,
            )
            local = add(local, sky)
        # shadow rays that crossed surfaces whose share varies: their shares, then the
        # lights once more with the answered visibilities (core.kernels.shadow_log)
        if WITH_VARYING_SHADOWS and answer_crossings(geo, surf, mats, ws, refraction_passes):
            continue
        break
    if WITH_CAUSTICS and lights.photon_cells.shape[0] > 0:
        falling = scale(caustic_irradiance(lights, p, n_geometric), 1.0 / math.pi)
        kd = phong.kd
        if phong.diffuse_roughness > 0.0:  # the photons' directions are not kept: the albedo
            mu_v = dot(point.normal, point.to_viewer)
            kd = rough_albedo(kd, phong.diffuse_roughness, frame.options[OPTION_ROUGH_DIFFUSE],
                              mu_v)  # fmt: skip
        local = add(local, mul(kd, falling))
        if splitting:  # the diffuse pass holds it, as light falling on the point
            for a in range(3):
                stacks.terms[TERM_ROW_LIT, a] += falling[a]
                stacks.terms[TERM_ROW_UNSHADOWED, a] += falling[a]
    return local
