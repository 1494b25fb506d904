"""What a hit means: its point, normals, texture coordinates and diffuse colour."""

import math

from ..jit import kernel
from .shapes import SHAPE_MESH, analytic_normal, analytic_uv
from .triangles import block_and_lane
from .vec import (
    add,
    affine_point,
    affine_transpose_vector,
    affine_vector,
    cross,
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


@kernel
def hit_coordinates(geo, surf, shape, p, n_world, u, v):
    """A hit's texture coordinates, as Blender's Texture Coordinate node gives them:
    (UV, Generated, Object, Normal), triples. Generated maps the shape's texture space (its
    box, core.compile.surfaces) to [0, 1]; Normal is the object-space normal (exact under
    rotations and uniform scales)."""
    transforms = geo.shape_object_from_world
    p_object = affine_point(transforms, shape, p)
    space = surf.shape_texspace
    generated = (
        (p_object[0] - space[shape, 0]) / (2.0 * space[shape, 3]) + 0.5,
        (p_object[1] - space[shape, 1]) / (2.0 * space[shape, 4]) + 0.5,
        (p_object[2] - space[shape, 2]) / (2.0 * space[shape, 5]) + 0.5,
    )
    n_object = affine_vector(transforms, shape, n_world)
    length = math.sqrt(n_object[0] ** 2 + n_object[1] ** 2 + n_object[2] ** 2)
    if length > 0.0:
        n_object = scale(n_object, 1.0 / length)
    return (u, v, 0.0), generated, p_object, n_object
