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
from ..vocabulary import (
    BUMP_DISPLACED,
    BUMP_UNCORRECTED,
    TERMINATOR_CHIANG,
    TERMINATOR_CONTY,
    TERMINATOR_NONE,
    TERMINATOR_SIDES,
)
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
def terminator_model(render_rule, material_rule):
    """The TERMINATOR_* a material's diffuse is lit by: the render's (OPTION_BUMP_TERMINATOR),
    none where its bend is its displacement, and without Bump Map Correction none (Chiang's)
    or only the side test (Conty's)."""
    if material_rule == BUMP_DISPLACED:
        return TERMINATOR_NONE
    if material_rule == BUMP_UNCORRECTED:
        return TERMINATOR_SIDES if render_rule == TERMINATOR_CONTY else TERMINATOR_NONE
    return render_rule


@kernel
def on_smooth_side(smooth, bent, light_dir, model):
    """Whether a glossy lobe about the bent normal is lit along light_dir: Conty's side
    test (below), which Cycles from 4.5 applies to every closure's light, not its
    softening; always under Chiang's rule or none."""
    if model != TERMINATOR_CONTY and model != TERMINATOR_SIDES:
        return True
    if bent[0] == smooth[0] and bent[1] == smooth[1] and bent[2] == smooth[2]:
        return True
    return dot(smooth, light_dir) * dot(smooth, bent) * dot(bent, light_dir) >= 0.0


@kernel
def terminator_term(smooth, bent, light_dir, model):
    """The share of a diffuse surface's light kept where a bent normal (Bump, Normal Map)
    meets a light near the smooth surface's shadow terminator, by rule `model`
    (TERMINATOR_*); 1 where the normal is not bent, or under TERMINATOR_NONE.

    Chiang, Li and Burley's ("Taming the Shadow Terminator", 2019; Cycles before 4.5):
    g = (S.L) / ((B.L)(S.B)), S the smooth normal and B the bent one; all the light where
    g >= 1, none where g < 0, else -g^3 + g^2 + g, which meets both ends smoothly.

    Conty Estevez, Lecocq and Stein's ("A Microfacet-Based Shadowing Function to Solve the
    Bump Terminator Problem", 2019; Cycles from 4.5): none where L and B lie on different
    sides of the smooth surface ((S.L)(S.B)(B.L) < 0), else the GGX masking G1 of the
    direction's angle to S, for a roughness alpha^2 = tan^2(d) / 8 of the bend d between S
    and B: 2 / (1 + sqrt(1 + alpha^2 tan^2 i)). TERMINATOR_SIDES keeps its side test only."""
    if model == TERMINATOR_NONE:
        return 1.0
    if bent[0] == smooth[0] and bent[1] == smooth[1] and bent[2] == smooth[2]:
        return 1.0
    cos_si = dot(smooth, light_dir)
    cos_sb = dot(smooth, bent)
    cos_bl = dot(bent, light_dir)
    if model != TERMINATOR_CHIANG:
        if cos_si * cos_sb * cos_bl < 0.0:
            return 0.0
        if model == TERMINATOR_SIDES:
            return 1.0
        cos_i, cos_d = abs(cos_si), abs(cos_sb)
        if cos_d >= 1.0 or cos_i >= 1.0:
            return 1.0
        if cos_i < 1e-6:
            return 0.0
        alpha2 = min(max(0.125 * (1.0 / (cos_d * cos_d) - 1.0), 0.0), 1.0)
        tan2 = 1.0 / (cos_i * cos_i) - 1.0
        return 2.0 / (1.0 + math.sqrt(1.0 + alpha2 * tan2))
    across = cos_bl * cos_sb
    if across == 0.0:
        return 1.0
    g = cos_si / across
    if g >= 1.0:
        return 1.0
    if g < 0.0:
        return 0.0
    return -g * g * g + g * g + g
