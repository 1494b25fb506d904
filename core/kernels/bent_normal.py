"""A shading normal bent by a Bump or Normal Map node, kept from reflecting below the surface.

A bent normal N can face the viewer so obliquely that the mirror direction of the incoming
ray about it, R = 2 (N.I) N - I (I the unit direction back to the viewer), points into the
surface: the reflected ray then meets the surface it left, and a smooth metal with a
normal map draws black crescents where Cycles shows the World. Cycles tilts such an N
towards the geometric normal Ng (on the viewer's side) just enough that R rises to a
small height above the surface, t = min(0.9 (I.Ng), 0.01): never steeper than the
incoming ray itself, and left alone where R is already that high. The lighting and every
closure of the surface then use the tilted normal, as here.

The tilt stays in the plane of Ng and N's part across the surface, X: N' = x X + z Ng with
x^2 + z^2 = 1 and R'.Ng = 2 z (N'.I) - I.Ng = t. With I = Ix X + Iy Y + Iz Ng, N'.I = x Ix +
z Iz, so 2 z x Ix = t + Iz - 2 z^2 Iz; squared, with x^2 = 1 - z^2, it is a quadratic in
s = z^2:

    4 a s^2 - 2 b s + c = 0,  a = Ix^2 + Iz^2,  b = 2 (a + Iz t),  c = (t + Iz)^2,

s = (b +- sqrt(b^2 - 4 a c)) / (4 a). Squaring lost the sign of 2 z x Ix, which is Ix's
(x, z >= 0): for Ix < 0 the right side must be <= 0, s >= (t + Iz) / (2 Iz), the larger
root; else the smaller. (Derived here; the rule and the threshold are Cycles'.)
"""

import math

from ..jit.decorators import kernel
from .vec import dot, normalize, scale, sub


@kernel
def kept_above(n_geometric, d, n):
    """The bent unit normal `n` (on n_geometric's side of the surface), tilted towards the
    geometric normal where a ray travelling along `d` would reflect about it into the
    surface; returned on the side it came."""
    wi = scale(d, -1.0)
    flip = dot(wi, n_geometric) < 0.0  # the ray comes from the back: work on its side
    ng = scale(n_geometric, -1.0) if flip else n_geometric
    m = scale(n, -1.0) if flip else n
    iz = dot(wi, ng)
    threshold = min(0.9 * iz, 0.01)
    cos_m = dot(m, wi)
    reflected_height = 2.0 * cos_m * dot(m, ng) - iz
    if reflected_height >= threshold:
        return n
    across = sub(m, scale(ng, dot(m, ng)))
    length = math.sqrt(dot(across, across))
    x_axis = scale(across, 1.0 / length) if length > 1e-12 else m
    ix = dot(wi, x_axis)
    a = ix * ix + iz * iz
    if a <= 1e-20:  # the ray runs along the surface, across N's tilt: nothing to lift
        return n
    b = 2.0 * (a + iz * threshold)
    c = (threshold + iz) * (threshold + iz)
    root = math.sqrt(max(b * b - 4.0 * a * c, 0.0))
    s = (b + root if ix < 0.0 else b - root) / (4.0 * a)
    z = math.sqrt(min(max(s, 0.0), 1.0))
    x = math.sqrt(max(1.0 - s, 0.0))
    tilted = normalize((x * x_axis[0] + z * ng[0], x * x_axis[1] + z * ng[1],
                        x * x_axis[2] + z * ng[2]))  # fmt: skip
    return scale(tilted, -1.0) if flip else tilted


@kernel
def terminator_term(smooth, bent, light_dir):
    """The share of a diffuse surface's light kept where a bent normal (Bump, Normal Map)
    turns it towards a light its own smooth normal faces away from: Chiang, Li and
    Burley's shadow terminator term ("Taming the Shadow Terminator", 2019), as Cycles
    weighs its diffuse closures by it. g = (S.L) / ((B.L)(S.B)), S the smooth normal and B
    the bent one; all the light where g >= 1, none where g < 0, else -g^3 + g^2 + g, which
    meets both ends smoothly. 1 where the normal is not bent."""
    if bent[0] == smooth[0] and bent[1] == smooth[1] and bent[2] == smooth[2]:
        return 1.0
    cos_bent = dot(bent, light_dir)
    across = cos_bent * dot(smooth, bent)
    if across == 0.0:
        return 1.0
    g = dot(smooth, light_dir) / across
    if g >= 1.0:
        return 1.0
    if g < 0.0:
        return 0.0
    return -g * g * g + g * g + g
