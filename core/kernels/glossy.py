"""Rough mirrors and glass: what their reflected and refracted rays are.

With RenderSettings.glossy_samples 0 (the core's default; Blender's is
core.model.settings.DEFAULT_GLOSSY_SAMPLES) a rough surface stays sharp: its one
reflected ray leaves by the mirror direction of the shading normal, its refracted ray by
Snell's law, each carrying what the rough lobe reflects or transmits on average (the
lobe's terms, core.kernels.shader_program), and its glint (core.kernels.microfacet) stands
for the lights it would blur (Surface.mirror_hides_lights). A scene that needs no blur pays
nothing for it.

With n > 0 samples, a camera ray's hit on a surface of roughness r spreads up to n rays
(n times the share of the light its lobes send on: core.kernels.integrator) over the
lobe, each by its own microfacet normal m drawn from GGX's distribution of normals visible
from the incoming direction (Heitz 2018, "Sampling the GGX Distribution of Visible
Normals"; Cycles' alpha is r^2): the mirror direction and Fresnel of m, Snell's law about
m, each ray carrying 1/n of the weight. Later hits spread one ray each, so a path's cost
grows with n once, not n^depth; more camera rays per pixel average the rest. A ray that m
sends below the surface it leaves is dropped: the light a microfacet's neighbours shadow.
"""

import math

from ..jit.decorators import kernel
from .light_samples import basis, in_frame
from .vec import add, cross, dot, normalize, scale


@kernel
def visible_normal(to_viewer, n, alpha, u1, u2):
    """A microfacet normal drawn from GGX's distribution of normals visible from unit
    `to_viewer` (above the surface of unit normal n), roughness alpha, by the uniform
    numbers u1, u2 in [0, 1)."""
    t, s = basis(n)
    v = (dot(to_viewer, t), dot(to_viewer, s), max(dot(to_viewer, n), 1e-9))
    # the view stretched to the unit-roughness configuration
    vh = normalize((alpha * v[0], alpha * v[1], v[2]))
    length2 = vh[0] * vh[0] + vh[1] * vh[1]
    if length2 > 0.0:
        inverse = 1.0 / math.sqrt(length2)
        t1 = (-vh[1] * inverse, vh[0] * inverse, 0.0)
    else:
        t1 = (1.0, 0.0, 0.0)
    t2 = cross(vh, t1)
    # a point on the disc, its half below the view's horizon squeezed away
    r = math.sqrt(u1)
    phi = 2.0 * math.pi * u2
    p1 = r * math.cos(phi)
    p2 = r * math.sin(phi)
    squeeze = 0.5 * (1.0 + vh[2])
    p2 = (1.0 - squeeze) * math.sqrt(max(0.0, 1.0 - p1 * p1)) + squeeze * p2
    up = math.sqrt(max(0.0, 1.0 - p1 * p1 - p2 * p2))
    nh = add(add(scale(t1, p1), scale(t2, p2)), scale(vh, up))
    # back to the surface's roughness, then to world space
    m = normalize((alpha * nh[0], alpha * nh[1], max(nh[2], 0.0)))
    return in_frame(n, m[0], m[1], m[2])
