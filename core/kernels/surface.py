"""What a hit means: its point, normals, texture coordinates and diffuse colour."""

import math

from core.jit import kernel
from core.kernels.shapes import SHAPE_MESH, analytic_normal, analytic_uv
from core.kernels.vec import (
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
def _vertex(ps, i):
    return (float(ps.vertices[i, 0]), float(ps.vertices[i, 1]), float(ps.vertices[i, 2]))


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
def surface_at(ps, shape, part, b1, b2, o, d, t):
    """(p, geometric normal, shading normal, u, v) at a hit, normals unit and outward.

    The shading normal differs from the geometric one only on smooth-shaded mesh faces,
    where the corner normals are interpolated with the barycentric weights.
    """
    m = ps.shape_object_from_world[shape]
    p = add(o, scale(d, t))
    kind = ps.shape_kind[shape]
    if kind != SHAPE_MESH:
        p_object = add(affine_point(m, o), scale(affine_vector(m, d), t))
        major = ps.shape_param[shape, 0]
        n = normalize(affine_transpose_vector(m, analytic_normal(kind, major, p_object, part)))
        u, v = analytic_uv(kind, major, p_object, part)
        return p, n, n, u, v

    mesh = ps.shape_mesh[shape]
    tri = part
    local = tri - ps.mesh_tri_offset[mesh]
    v0 = _vertex(ps, ps.tri_vertices[tri, 0])
    v1 = _vertex(ps, ps.tri_vertices[tri, 1])
    v2 = _vertex(ps, ps.tri_vertices[tri, 2])
    geometric = normalize(affine_transpose_vector(m, cross(sub(v1, v0), sub(v2, v0))))
    b0 = 1.0 - b1 - b2
    shading = geometric
    normal_row = ps.mesh_normal_offset[mesh]
    if normal_row >= 0 and ps.tri_smooth[tri]:
        n_object = _blend3(ps.normals, ps.tri_normal_index, normal_row + local, b0, b1, b2)
        n_world = affine_transpose_vector(m, n_object)
        if n_world[0] != 0.0 or n_world[1] != 0.0 or n_world[2] != 0.0:
            shading = normalize(n_world)
    u = v = 0.0
    uv_row = ps.mesh_uv_offset[mesh]
    if uv_row >= 0:
        r = uv_row + local
        i0, i1, i2 = ps.tri_uv_index[r, 0], ps.tri_uv_index[r, 1], ps.tri_uv_index[r, 2]
        u = b0 * ps.uvs[i0, 0] + b1 * ps.uvs[i1, 0] + b2 * ps.uvs[i2, 0]
        v = b0 * ps.uvs[i0, 1] + b1 * ps.uvs[i1, 1] + b2 * ps.uvs[i2, 1]
    return p, geometric, shading, u, v


@kernel
def _texel(ps, texture, x, y):
    width, height = ps.texture_size[texture, 0], ps.texture_size[texture, 1]
    i = ps.texture_offset[texture] + (y % height) * width + (x % width)
    return (
        float(ps.texture_pixels[i, 0]),
        float(ps.texture_pixels[i, 1]),
        float(ps.texture_pixels[i, 2]),
    )


@kernel
def diffuse_colour(ps, material, u, v):
    """The material's kd, or its texture at (u, v): bilinear, repeating, v = 0 at the
    bottom row of the image."""
    texture = ps.material_texture[material]
    if texture < 0:
        return row(ps.material_diffuse, material)
    width, height = ps.texture_size[texture, 0], ps.texture_size[texture, 1]
    x = u * width - 0.5
    y = (1.0 - v) * height - 0.5
    if not (math.isfinite(x) and math.isfinite(y)):
        return _texel(ps, texture, 0, 0)
    x0, y0 = math.floor(x), math.floor(y)
    fx, fy = x - x0, y - y0
    i, j = int(x0), int(y0)
    top = add(scale(_texel(ps, texture, i, j), 1.0 - fx), scale(_texel(ps, texture, i + 1, j), fx))
    bottom = add(
        scale(_texel(ps, texture, i, j + 1), 1.0 - fx), scale(_texel(ps, texture, i + 1, j + 1), fx)
    )
    return add(scale(top, 1.0 - fy), scale(bottom, fy))
