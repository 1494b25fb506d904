"""Blender's Translucent BSDF: Lambertian transmission. A surface of translucent colour k
passes on k/pi of the light falling on its other side, spread evenly over the side the
viewer is on: the light of a lamp behind a sheet of paper, a leaf against the sun.

With Cycles' diffuse bounces 0 the light seen is what falls on the back directly (lamps,
the sun, the World, caustics), as for a diffuse surface's front: so it is the shading of a
diffuse surface of colour k at the same point facing the other way (its shadow rays leave
from the back, its World is the back hemisphere), `light_at_point` run once more with the
normals turned. A call of its own behind the `translucent` feature, as every copy of
`light_at_point` adds to the cold compile.
"""

from ..jit.decorators import kernel
from ..vocabulary import TERMINATOR_NONE
from .clear_coat import NO_GLINT
from .features import WITH_TRANSLUCENT
from .light_at_point import light_at_point
from .shading import Phong, ShadingPoint
from .trace import spawn_point
from .vec import scale


@kernel
def translucent_light(frame, lights, geo, surf, mats, ws, colour, p, n_shading, n_geometric,
                      o, d, key, event, refraction_passes):  # fmt: skip
    """The light a surface of translucent `colour` (RGB, its share of the surface already
    in it) at p passes on towards the viewer from its other side; n_shading and n_geometric
    face the viewer, d is the ray's direction from o."""
    if not WITH_TRANSLUCENT:
        return 0.0, 0.0, 0.0
    back = scale(n_geometric, -1.0)
    turned = scale(n_shading, -1.0)
    point = ShadingPoint(spawn_point(p, back, o), turned, d, turned, TERMINATOR_NONE)
    phong = Phong(colour, (0.0, 0.0, 0.0), 1.0, NO_GLINT, turned, (1.0, 1.0, 1.0), NO_GLINT,
                  turned, 0.0)  # fmt: skip
    return light_at_point(frame, lights, geo, surf, mats, ws, point, phong, p, back, key,
                          event, False, refraction_passes)  # fmt: skip
