"""Blender's Fresnel and Layer Weight nodes: numbers from how squarely a ray meets the
surface, which library materials mix glass edges, car paint and rim light by.

Both take I (towards where the ray came from), a normal N and whether the ray met the
surface's back (its geometric normal facing away from the ray), as Cycles' nodes do:

- Fresnel: the unpolarised dielectric reflectance for |I . N| at relative index IOR, or
  1 / IOR on the back; 1 past the critical angle (total internal reflection);
- Layer Weight's Fresnel: the same with the index 1 / (1 - Blend) (on the back 1 - Blend),
  so Blend 0.5 is an index of 2;
- Layer Weight's Facing: 1 - |I . N|^p, with p = 2 Blend below a Blend of 0.5 and
  0.5 / (1 - Blend) above it (1 at 0.5: 1 - |I . N| itself).

Only |I . N| is read, so the normal may face either way (Whitted's shading normal faces
out of the surface; Cycles' faces the ray).
"""

from ..jit.decorators import kernel
from .fresnel import fresnel_dielectric
from .vec import dot

FACING_FRESNEL, FACING_LAYER_FRESNEL, FACING_LAYER_FACING = 0, 1, 2


@kernel
def facing_value(which, value, incoming, normal, backfacing):
    """The node's output `which` (FACING_*) for its IOR or Blend `value`, `incoming` the
    unit vector I and `normal` a unit normal."""
    facing = min(abs(dot(incoming, normal)), 1.0)
    if which == FACING_FRESNEL:
        eta = max(value, 1e-5)  # the index beyond the surface over the one the ray is in
        return fresnel_dielectric(facing, 1.0, 1.0 / eta if backfacing else eta)[0]
    if which == FACING_LAYER_FRESNEL:
        eta = max(1.0 - value, 1e-5)
        return fresnel_dielectric(facing, 1.0, eta if backfacing else 1.0 / eta)[0]
    if value != 0.5:
        blend = min(max(value, 0.0), 1.0 - 1e-5)
        power = 2.0 * blend if blend < 0.5 else 0.5 / (1.0 - blend)
        facing = facing**power
    return 1.0 - facing
