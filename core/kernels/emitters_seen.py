"""Lights in Blender's units seen in mirrors and through glass, as Cycles shows them.

A reflected or refracted ray that passes through a light before its nearest hit adds the
light's radiance (times the ray's weight) and goes on: in Cycles lights are not opaque, and
the camera does not see them directly. A light is seen by reflected rays if its Glossy Ray
Visibility is on, by refracted rays if its Transmission is.

- a panel, from its shining side: L = P / (pi area)
- a sphere, or a disk of the radius turned to the ray's origin (Soft Falloff):
  P / (4 pi^2 r^2), the radiance that lights surfaces
- a spot light: the same, masked as its light leaves along the ray back
- a sun with an angle, to rays that leave the scene within it: S / (pi sin^2 h) (a cone,
  Blender 4.0 on), or S / (pi tan^2 h) (Blender 3.x's disk)
"""

import math

from ..jit.decorators import kernel
from .layout import EMITS_SPECULAR, EMITS_SPOT, EMITS_SPOT_COSINE, EMITS_TRANSMISSION
from .light_sphere import spot_mask
from .options import (
    EMITTER_ELLIPSE,
    EMITTER_FACING_DISK,
    EMITTER_RECTANGLE,
    EMITTER_SPHERE,
    EMITTER_SUN_CONE,
)
from .vec import add, cross, dot, normalize, row, scale, sub


@kernel
def _frame_row(frames, light, k):
    return (frames[light, k, 0], frames[light, k, 1], frames[light, k, 2])


@kernel
def _panel_crossing(lights, light, o, d, t_max):
    """The ray's distance to the panel's shining side, or -1 if it misses it."""
    frames = lights.emitter_frame
    edge_u, edge_v = _frame_row(frames, light, 0), _frame_row(frames, light, 1)
    facing = _frame_row(frames, light, 2)
    towards = dot(d, facing)
    if towards >= 0.0:
        return -1.0  # travelling with its light, or along it: the panel's back or edge
    centre = row(lights.emitter_position, light)
    t = dot(sub(centre, o), facing) / towards
    if not (0.0 < t < t_max):
        return -1.0
    offset = sub(add(o, scale(d, t)), centre)
    # The hit's coordinates s, q along the edges (p = centre + s edge_u + q edge_v)
    uu, uv, vv = dot(edge_u, edge_u), dot(edge_u, edge_v), dot(edge_v, edge_v)
    ou, ov = dot(offset, edge_u), dot(offset, edge_v)
    det = uu * vv - uv * uv
    s = (ou * vv - ov * uv) / det
    q = (ov * uu - ou * uv) / det
    if lights.emitter_kind[light] == EMITTER_ELLIPSE:
        inside = 4.0 * (s * s + q * q) <= 1.0
    else:
        inside = abs(s) <= 0.5 and abs(q) <= 0.5
    return t if inside else -1.0


@kernel
def _round_crossing(lights, light, o, d, t_max):
    """The ray's distance to a sphere light, or to a facing disk light, or -1."""
    centre = row(lights.emitter_position, light)
    radius = lights.emitter_param[light, 0]
    if radius <= 0.0:
        return -1.0
    to_origin = sub(o, centre)
    if lights.emitter_kind[light] == EMITTER_SPHERE:
        b = dot(to_origin, d)
        c = dot(to_origin, to_origin) - radius * radius
        disc = b * b - c
        if disc < 0.0:
            return -1.0
        root = math.sqrt(disc)
        t = -b - root if -b - root > 0.0 else -b + root
        return t if 0.0 < t < t_max else -1.0
    facing = normalize(to_origin)
    towards = dot(d, facing)
    if towards >= 0.0:
        return -1.0
    t = -dot(to_origin, facing) / towards
    if not (0.0 < t < t_max):
        return -1.0
    offset = add(to_origin, scale(d, t))
    return t if dot(offset, offset) <= radius * radius else -1.0


@kernel
def emitters_seen(lights, o, d, t_max, refracted):
    """The radiance of the lights a reflected (or, with `refracted`, a refracted) ray from o
    along unit d passes through before distance t_max (inf: it leaves the scene)."""
    seen = (0.0, 0.0, 0.0)
    needed = EMITS_TRANSMISSION if refracted else EMITS_SPECULAR
    param = lights.emitter_param
    for light in range(lights.emitter_kind.shape[0]):
        flags = lights.emitter_flags[light]
        if not flags & needed:
            continue
        kind = lights.emitter_kind[light]
        radiance = row(lights.emitter_radiance, light)
        if kind >= EMITTER_SUN_CONE:
            one_minus_cos = param[light, 0]
            if t_max != math.inf or one_minus_cos == 0.0:
                continue
            toward = row(lights.emitter_position, light)
            if 1.0 - dot(d, toward) > one_minus_cos:
                continue
            if kind == EMITTER_SUN_CONE:
                # radiance S / (pi sin^2 h); the table holds (S / pi) 2 / (1 + cos h)
                seen = add(seen, scale(radiance, 0.5 / one_minus_cos))
            else:
                tan_half = param[light, 1]
                seen = add(seen, scale(radiance, 1.0 / (tan_half * tan_half)))
            continue
        if EMITTER_RECTANGLE <= kind <= EMITTER_ELLIPSE:
            if _panel_crossing(lights, light, o, d, t_max) < 0.0:
                continue
            frames = lights.emitter_frame
            edges = cross(_frame_row(frames, light, 0), _frame_row(frames, light, 1))
            area = math.sqrt(dot(edges, edges)) * (
                0.25 * math.pi if kind == EMITTER_ELLIPSE else 1.0
            )
            # radiance P / (pi area); the table holds P / pi^2
            seen = add(seen, scale(radiance, math.pi / area))
            continue
        if kind > EMITTER_FACING_DISK or _round_crossing(lights, light, o, d, t_max) < 0.0:
            continue
        radius = param[light, 0]
        # radiance P / (4 pi^2 r^2); the table holds P / (4 pi^2)
        share = 1.0 / (radius * radius)
        if flags & EMITS_SPOT:
            to_light_frame = (
                _frame_row(lights.emitter_frame, light, 0),
                _frame_row(lights.emitter_frame, light, 1),
                _frame_row(lights.emitter_frame, light, 2),
            )
            with_cosine = (flags & EMITS_SPOT_COSINE) != 0
            share *= spot_mask(
                to_light_frame, scale(d, -1.0), param[light, 1], param[light, 2], with_cosine
            )
        seen = add(seen, scale(radiance, share))
    return seen
