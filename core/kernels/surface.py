"""What a hit means: its point, normals, texture coordinates and diffuse colour."""

import math

from ..jit.decorators import kernel
from .shapes import SHAPE_MESH, analytic_normal, analytic_uv
from .triangles import block_and_lane
from .vec import (
    add,
    affine_point,
    affine_transpose_vector,
    affine_vector,
    cross,
    dot,
    normalize,
    row,
    scale,
    sub,
)


@kernel
def _corner(corners, slot, first):
    """Corner (rows first .. first + 2) of the triangle in slot `slot` of the leaf blocks."""
    block, lane = block_and_lane(slot)
    return (
        float(corners[block, first, lane]),
        float(corners[block, first + 1, lane]),
        float(corners[block, first + 2, lane]),
    )


@kernel
def _blend3(table, index, row_, b0, b1, b2):
    """b0 table[index[row, 0]] + b1 table[index[row, 1]] + b2 table[index[row, 2]]."""
    i0, i1, i2 = index[row_, 0], index[row_, 1], index[row_, 2]
    return (
        b0 * table[i0, 0] + b1 * table[i1, 0] + b2 * table[i2, 0],
        b0 * table[i0, 1] + b1 * table[i1, 1] + b2 * table[i2, 1],
        b0 * table[i0, 2] + b1 * table[i1, 2] + b2 * table[i2, 2],
    )


@kernel
def surface_at(geo, surf, shape, part, b1, b2, o, d, t, with_uv):
    """(p, geometric normal, shading normal, u, v) at a hit, normals unit and outward;
    u = v = 0 unless with_uv (texture coordinates cost trigonometry on analytic shapes).
    A part stored as ~part (a CSG surface facing into its solid) gets its normals flipped
    and keeps its own texture coordinates.
    """
    if part < 0:
        p, n_geometric, n_shading, u, v = _outward_surface(
            geo, surf, shape, ~part, b1, b2, o, d, t, with_uv
        )
        return p, scale(n_geometric, -1.0), scale(n_shading, -1.0), u, v
    return _outward_surface(geo, surf, shape, part, b1, b2, o, d, t, with_uv)


@kernel
def _outward_surface(geo, surf, shape, part, b1, b2, o, d, t, with_uv):
    """`surface_at` for a part as stored by the shape itself. The shading normal differs
    from the geometric one only on smooth-shaded mesh faces, where the corner normals are
    interpolated with the barycentric weights."""
    transforms = geo.shape_object_from_world
    p = add(o, scale(d, t))
    kind = geo.shape_kind[shape]
    u = v = 0.0
    if kind != SHAPE_MESH:
        p_object = add(
            affine_point(transforms, shape, o), scale(affine_vector(transforms, shape, d), t)
        )
        major = geo.shape_param[shape, 0]
        n_object = analytic_normal(kind, major, p_object, part)
        n = normalize(affine_transpose_vector(transforms, shape, n_object))
        if with_uv:
            u, v = analytic_uv(kind, major, p_object, part)
        return p, n, n, u, v

    mesh = geo.shape_index[shape]
    tri = part
    local = tri - surf.mesh_tri_offset[mesh]
    corners = geo.tri_corners
    v0 = _corner(corners, tri, 0)
    v1 = _corner(corners, tri, 3)
    v2 = _corner(corners, tri, 6)
    face = cross(sub(v1, v0), sub(v2, v0))
    geometric = normalize(affine_transpose_vector(transforms, shape, face))
    b0 = 1.0 - b1 - b2
    shading = geometric
    normal_row = surf.mesh_normal_offset[mesh]
    if normal_row >= 0 and surf.tri_smooth[tri]:
        n_object = _blend3(surf.normals, surf.tri_normal_index, normal_row + local, b0, b1, b2)
        n_world = affine_transpose_vector(transforms, shape, n_object)
        if n_world[0] != 0.0 or n_world[1] != 0.0 or n_world[2] != 0.0:
            shading = normalize(n_world)
    uv_row = surf.mesh_uv_offset[mesh]
    if with_uv and uv_row >= 0:
        r = uv_row + local
        index, uvs = surf.tri_uv_index, surf.uvs
        i0, i1, i2 = index[r, 0], index[r, 1], index[r, 2]
        u = b0 * uvs[i0, 0] + b1 * uvs[i1, 0] + b2 * uvs[i2, 0]
        v = b0 * uvs[i0, 1] + b1 * uvs[i1, 1] + b2 * uvs[i2, 1]
    return p, geometric, shading, u, v


@kernel
def _texel(pixels, first, width, height, x, y):
    i = first + (y % height) * width + (x % width)
    return float(pixels[i, 0]), float(pixels[i, 1]), float(pixels[i, 2])


@kernel
def bilinear(pixels, first, width, height, u, v):
    """The image of `width` x `height` texels from pixels[first] at (u, v): bilinear,
    repeating, v = 0 at the bottom row of the image."""
    x = u * width - 0.5
    y = (1.0 - v) * height - 0.5
    if not (math.isfinite(x) and math.isfinite(y)):
        return _texel(pixels, first, width, height, 0, 0)
    x0, y0 = math.floor(x), math.floor(y)
    fx, fy = x - x0, y - y0
    i, j = int(x0), int(y0)
    top = add(
        scale(_texel(pixels, first, width, height, i, j), 1.0 - fx),
        scale(_texel(pixels, first, width, height, i + 1, j), fx),
    )
    bottom = add(
        scale(_texel(pixels, first, width, height, i, j + 1), 1.0 - fx),
        scale(_texel(pixels, first, width, height, i + 1, j + 1), fx),
    )
    return add(scale(top, 1.0 - fy), scale(bottom, fy))


@kernel
def nearest(pixels, first, width, height, u, v):
    """The texel (u, v) falls in, repeating; v = 0 at the bottom row."""
    x, y = u * width, (1.0 - v) * height
    if not (math.isfinite(x) and math.isfinite(y)):
        return _texel(pixels, first, width, height, 0, 0)
    return _texel(pixels, first, width, height, int(math.floor(x)), int(math.floor(y)))


@kernel
def diffuse_colour(mats, material, u, v):
    """The material's kd, or its texture at (u, v) (`bilinear`)."""
    texture = mats.texture[material]
    if texture < 0:
        return row(mats.diffuse, material)
    pixels, first = mats.texture_pixels, mats.texture_offset[texture]
    width, height = mats.texture_size[texture, 0], mats.texture_size[texture, 1]
    return bilinear(pixels, first, width, height, u, v)


# Bump mapping's finite differences step this far across the surface, in object space,
# relative to the point's distance from the object's origin (at least 1)
BUMP_STEP = 1e-4


@kernel
def _coordinates(surf, shape, p_object, n_object, u, v):
    """(UV, Generated, Object, Normal) triples at an object-space point."""
    space = surf.shape_texspace
    generated = (
        (p_object[0] - space[shape, 0]) / (2.0 * space[shape, 3]) + 0.5,
        (p_object[1] - space[shape, 1]) / (2.0 * space[shape, 4]) + 0.5,
        (p_object[2] - space[shape, 2]) / (2.0 * space[shape, 5]) + 0.5,
    )
    return (u, v, 0.0), generated, p_object, n_object


@kernel
def _mesh_uv_gradient(geo, surf, shape, tri):
    """(dP/du, dP/dv) in object space over a mesh triangle, from its corners and UVs; zero
    vectors when it has none (or they are degenerate)."""
    mesh = geo.shape_index[shape]
    uv_row = surf.mesh_uv_offset[mesh]
    zero = (0.0, 0.0, 0.0)
    if uv_row < 0:
        return zero, zero
    r = uv_row + tri - surf.mesh_tri_offset[mesh]
    index, uvs = surf.tri_uv_index, surf.uvs
    i0, i1, i2 = index[r, 0], index[r, 1], index[r, 2]
    du1, dv1 = uvs[i1, 0] - uvs[i0, 0], uvs[i1, 1] - uvs[i0, 1]
    du2, dv2 = uvs[i2, 0] - uvs[i0, 0], uvs[i2, 1] - uvs[i0, 1]
    det = du1 * dv2 - du2 * dv1
    if det == 0.0:
        return zero, zero
    corners = geo.tri_corners
    v0 = _corner(corners, tri, 0)
    e1, e2 = sub(_corner(corners, tri, 3), v0), sub(_corner(corners, tri, 6), v0)
    dp_du = scale(sub(scale(e1, dv2), scale(e2, dv1)), 1.0 / det)
    dp_dv = scale(sub(scale(e2, du1), scale(e1, du2)), 1.0 / det)
    return dp_du, dp_dv


@kernel
def hit_frame(geo, surf, shape, part, p, n_world, u, v, with_frame):
    """A hit's texture coordinates, as Blender's Texture Coordinate node gives them, at the
    hit and at two points a small step away across the surface (for Bump's differences):
    ((UV, Generated, Object, Normal) x 3), and in world space the two steps (along
    increasing u, and v) and the normal. Generated maps the shape's texture space
    (core.compile.surfaces) to [0, 1]; Normal is the object-space normal (exact under
    rotations and uniform scales). Tangents: a mesh triangle's UV gradient (Cycles
    interpolates MikkTSpace tangents over the vertices); on analytic shapes the direction
    of u, round the z axis. Without `with_frame` (no Bump or Normal Map in the material's
    program) only the hit's own coordinates are made: the steps are left zero."""
    transforms = geo.shape_object_from_world
    p_object = affine_point(transforms, shape, p)
    n_object = normalize(affine_vector(transforms, shape, n_world))
    base = _coordinates(surf, shape, p_object, n_object, u, v)
    if not with_frame:
        zero = (0.0, 0.0, 0.0)
        return (base, base, base), (zero, zero, n_world)
    kind = geo.shape_kind[shape]
    if kind == SHAPE_MESH:
        dp_du, dp_dv = _mesh_uv_gradient(geo, surf, shape, part)
    else:
        dp_du = cross((0.0, 0.0, 1.0), n_object)
        dp_dv = cross(n_object, dp_du)
    if dot(dp_du, dp_du) == 0.0:  # no UVs: any direction across the surface
        helper = (1.0, 0.0, 0.0) if abs(n_object[0]) < 0.9 else (0.0, 1.0, 0.0)
        dp_du = cross(helper, n_object)
        dp_dv = cross(n_object, dp_du)
    # The object-space tangent frame, made orthonormal about the normal
    t_object = normalize(sub(dp_du, scale(n_object, dot(dp_du, n_object))))
    b_object = cross(n_object, t_object)
    if dot(b_object, dp_dv) < 0.0:
        b_object = scale(b_object, -1.0)
    step = BUMP_STEP * max(1.0, math.sqrt(dot(p_object, p_object)))
    # UVs one step along each direction: the UV gradient's inverse, by projection
    uu, vv = dot(dp_du, dp_du), dot(dp_dv, dp_dv)
    du_t = dot(t_object, dp_du) / uu if uu > 0.0 else 0.0
    dv_t = dot(t_object, dp_dv) / vv if vv > 0.0 else 0.0
    du_b = dot(b_object, dp_du) / uu if uu > 0.0 else 0.0
    dv_b = dot(b_object, dp_dv) / vv if vv > 0.0 else 0.0
    p_x = add(p_object, scale(t_object, step))
    p_y = add(p_object, scale(b_object, step))
    if kind == SHAPE_MESH:
        u_x, v_x = u + step * du_t, v + step * dv_t
        u_y, v_y = u + step * du_b, v + step * dv_b
    else:
        u_x, v_x = analytic_uv(kind, geo.shape_param[shape, 0], p_x, part)
        u_y, v_y = analytic_uv(kind, geo.shape_param[shape, 0], p_y, part)
    along_x = _coordinates(surf, shape, p_x, n_object, u_x, v_x)
    along_y = _coordinates(surf, shape, p_y, n_object, u_y, v_y)
    # The steps in world space, and the normal as given
    dp_x = _to_world(transforms, shape, scale(t_object, step))
    dp_y = _to_world(transforms, shape, scale(b_object, step))
    return (base, along_x, along_y), (dp_x, dp_y, n_world)


@kernel
def _to_world(transforms, shape, v_object):
    """An object-space vector in world space: the inverse of affine_vector, by solving the
    3 x 3 system (the table keeps object-from-world only)."""
    m = transforms
    a, b, c = m[shape, 0, 0], m[shape, 0, 1], m[shape, 0, 2]
    d, e, f = m[shape, 1, 0], m[shape, 1, 1], m[shape, 1, 2]
    g, h, i = m[shape, 2, 0], m[shape, 2, 1], m[shape, 2, 2]
    det = a * (e * i - f * h) - b * (d * i - f * g) + c * (d * h - e * g)
    if det == 0.0:
        return v_object
    x, y, z = v_object
    return (
        ((e * i - f * h) * x - (b * i - c * h) * y + (b * f - c * e) * z) / det,
        (-(d * i - f * g) * x + (a * i - c * g) * y - (a * f - c * d) * z) / det,
        ((d * h - e * g) * x - (a * h - b * g) * y + (a * e - b * d) * z) / det,
    )


@kernel
def normal_rows(transforms, shape):
    """Rows of the object-to-world normal transform: the object-from-world matrix's
    transpose (normals transform by the inverse transpose)."""
    m = transforms
    return (
        (m[shape, 0, 0], m[shape, 1, 0], m[shape, 2, 0]),
        (m[shape, 0, 1], m[shape, 1, 1], m[shape, 2, 1]),
        (m[shape, 0, 2], m[shape, 1, 2], m[shape, 2, 2]),
    )
