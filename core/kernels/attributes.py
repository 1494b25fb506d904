"""A mesh's colour attributes at a hit (Blender's Color Attribute and Attribute nodes): each
attribute the scene's programs read, k = 0, 1, ... in core.model.shader.attribute_names'
order, interpolated over the hit triangle from its corners' RGBA by the barycentric
weights of the hit point, and left on the program's stack at attribute_slot(k), where
OP_ATTRIBUTE reads it. A shape without the attribute (an analytic shape, a mesh that lacks
it) reads zero, as Cycles reads a missing attribute.

One attribute is computed, not stored (core.model.shader.EDGE_ATTRIBUTE, the Wireframe
node's): the distances, in world units, from the hit point to the lines of its triangle's
three edges, as Cycles measures them for the Wireframe node, and 1 (zeros off a mesh,
which has no edges to draw).

Called before the program runs, only for a material whose program reads attributes
(Materials.shader_frame's READS_ATTRIBUTES bit).
"""

import math

from ..jit.decorators import kernel
from .shader_program import SHADER_STACK
from .shapes import SHAPE_MESH
from .surface import _corner  # a leaf block's triangle corner
from .vec import affine_point, cross, dot, sub

# Meshes.color_offset's mark for the computed edge distances (core.compile.meshes)
EDGE_DISTANCES = -2

# Materials.shader_frame's bits: what a program reads beyond the hit's own coordinates
READS_FRAME = 1  # the surface's tangents and steps across it (Bump, Normal Map)
READS_ATTRIBUTES = 2  # colour attributes


@kernel
def _barycentric(geo, tri, p_object):
    """(b0, b1, b2) of the object-space point in mesh triangle slot `tri` (projected on
    its plane)."""
    corners = geo.tri_corners
    v0 = _corner(corners, tri, 0)
    e1 = sub(_corner(corners, tri, 3), v0)
    e2 = sub(_corner(corners, tri, 6), v0)
    w = sub(p_object, v0)
    d00, d01, d11 = dot(e1, e1), dot(e1, e2), dot(e2, e2)
    d20, d21 = dot(w, e1), dot(w, e2)
    det = d00 * d11 - d01 * d01
    if det == 0.0:
        return 1.0, 0.0, 0.0
    b1 = (d11 * d20 - d01 * d21) / det
    b2 = (d00 * d21 - d01 * d20) / det
    return 1.0 - b1 - b2, b1, b2


@kernel
def _world_rows(geo, shape):
    """Rows of the shape's object-to-world linear map (for directions): the inverse of its
    object-from-world rows' linear part, by cofactors; the identity if it is singular."""
    m = geo.shape_object_from_world
    a, b, c = m[shape, 0, 0], m[shape, 0, 1], m[shape, 0, 2]
    d, e, f = m[shape, 1, 0], m[shape, 1, 1], m[shape, 1, 2]
    g, h, i = m[shape, 2, 0], m[shape, 2, 1], m[shape, 2, 2]
    ca, cb, cc = e * i - f * h, f * g - d * i, d * h - e * g
    det = a * ca + b * cb + c * cc
    if det == 0.0:
        return (1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0)
    return (
        (ca / det, (c * h - b * i) / det, (b * f - c * e) / det),
        (cb / det, (a * i - c * g) / det, (c * d - a * f) / det),
        (cc / det, (b * g - a * h) / det, (a * e - b * d) / det),
    )


@kernel
def _apply(rows, v):
    return dot(rows[0], v), dot(rows[1], v), dot(rows[2], v)


@kernel
def _line_distance(rows, a, b, p_object):
    """World distance from the object-space point to the line through corners a and b
    (`rows`: _world_rows): |(p - a) x (b - a)| / |b - a|, as Cycles' Wireframe measures it."""
    edge = _apply(rows, sub(b, a))
    to_p = _apply(rows, sub(p_object, a))
    along = dot(edge, edge)
    if along == 0.0:
        return math.sqrt(dot(to_p, to_p))
    c = cross(to_p, edge)
    return math.sqrt(dot(c, c) / along)


@kernel
def edge_distances(geo, shape, tri, p_object):
    """World distances from the object-space point to the lines of mesh triangle slot
    `tri`'s edges 0-1, 1-2 and 2-0."""
    corners, rows = geo.tri_corners, _world_rows(geo, shape)
    a, b, c = _corner(corners, tri, 0), _corner(corners, tri, 3), _corner(corners, tri, 6)
    return (_line_distance(rows, a, b, p_object),
            _line_distance(rows, b, c, p_object),
            _line_distance(rows, c, a, p_object))  # fmt: skip


@kernel
def put_attributes(geo, surf, shape, part, p, stack):
    """Write every colour attribute at world point p of shape row `shape` (mesh triangle
    slot `part`) to the stack's top (the module's layout)."""
    count = surf.mesh_color_offset.shape[1]
    mesh = geo.shape_index[shape] if geo.shape_kind[shape] == SHAPE_MESH else -1
    weights = (0.0, 0.0, 0.0)
    p_object = p
    if mesh >= 0:
        p_object = affine_point(geo.shape_object_from_world, shape, p)
        weights = _barycentric(geo, part, p_object)
    for k in range(count):
        slot = SHADER_STACK - 4 * (k + 1)
        first = surf.mesh_color_offset[mesh, k] if mesh >= 0 else -1
        if first == EDGE_DISTANCES:
            d0, d1, d2 = edge_distances(geo, shape, part, p_object)
            stack[slot], stack[slot + 1], stack[slot + 2], stack[slot + 3] = d0, d1, d2, 1.0
            continue
        if first < 0:
            for c in range(4):
                stack[slot + c] = 0.0
            continue
        r = first + part - surf.mesh_tri_offset[mesh]
        index, colours = surf.tri_color_index, surf.colors
        i0, i1, i2 = index[r, 0], index[r, 1], index[r, 2]
        for c in range(4):
            stack[slot + c] = (weights[0] * colours[i0, c] + weights[1] * colours[i1, c]
                               + weights[2] * colours[i2, c])  # fmt: skip
