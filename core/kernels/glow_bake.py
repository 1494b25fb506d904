"""An emissive mesh whose emission varies over its surface (an image in the Principled BSDF's
Emission Color, as Blender's glTF importer links every emissive map; a procedural texture),
made a light (core.compile.glowing): each of its triangles cut into level x level equal
sub-triangles, and each sub-triangle's emission the mean of the material's program run at
four points of it (the centroids of its quarters: exact for emission linear over it).

The light then samples sub-triangles in proportion to their area times their mean emission
(core.kernels.light_mesh), each shining its own colour: emission that is constant over a
sub-triangle is lit exactly; finer detail is averaged over the sub-triangle, which matters
only for a point nearer the surface than a few sub-triangles across.

A compile-time kernel, run once a scene: the packing's warm-up compiles it
(core.jit.warmup's scene holds such a mesh).
"""

import math

from ..jit.decorators import kernel
from .material_at_hit import run_program_at
from .surface import _corner, surface_at
from .surface_terms import terms_from_lobes
from .vec import add, affine, scale, sub

# The four points each sub-triangle's emission is the mean of: the centroids of its quarters,
# as weights of its corners
_QUARTERS = (
    (2.0 / 3.0, 1.0 / 6.0, 1.0 / 6.0),
    (1.0 / 6.0, 2.0 / 3.0, 1.0 / 6.0),
    (1.0 / 6.0, 1.0 / 6.0, 2.0 / 3.0),
    (1.0 / 3.0, 1.0 / 3.0, 1.0 / 3.0),
)


@kernel
def _emission_at(geo, surf, mats, shape, material, slot, b1, b2, p, stack, lobes):
    """The material's emission at world point p, weights (b1, b2) of triangle `slot`: the
    program run as at a hit (core.kernels.material_at_hit), for no ray in particular (a
    light's sample: Light Path reads 0 everywhere, as Cycles' emission evaluation reads)."""
    _, _, n_shading, u, v = surface_at(geo, surf, shape, slot, b1, b2, p, (0.0, 0.0, 1.0),
                                       0.0, True)  # fmt: skip
    nobody = (0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0,
              0.0, 0.0, 0.0, 0.0, 0.0, 0.0)  # fmt: skip
    run_program_at(geo, surf, mats, shape, material, slot, p, n_shading, u, v, stack, lobes,
                   nobody)  # fmt: skip
    return terms_from_lobes(lobes).emission


@kernel
def _bake_one(geo, surf, mats, world_from_object, shape, material, slot, corners, o, row,
              stack, lobes):  # fmt: skip
    """Write sub-triangle `corners` ((b1, b2) of each, in triangle `slot`) to out[row]:
    its world corners, then its mean emission."""
    v0 = _corner(geo.tri_corners, slot, 0)
    e1 = sub(_corner(geo.tri_corners, slot, 3), v0)
    e2 = sub(_corner(geo.tri_corners, slot, 6), v0)
    for c in range(3):
        p = affine(world_from_object, add(v0, add(scale(e1, corners[c][0]),
                                                  scale(e2, corners[c][1]))))  # fmt: skip
        o[row, 3 * c], o[row, 3 * c + 1], o[row, 3 * c + 2] = p
    total = (0.0, 0.0, 0.0)
    for q in range(4):
        w = _QUARTERS[q]
        b1 = w[0] * corners[0][0] + w[1] * corners[1][0] + w[2] * corners[2][0]
        b2 = w[0] * corners[0][1] + w[1] * corners[1][1] + w[2] * corners[2][1]
        p = affine(world_from_object, add(v0, add(scale(e1, b1), scale(e2, b2))))
        total = add(total, _emission_at(geo, surf, mats, shape, material, slot, b1, b2, p,
                                        stack, lobes))  # fmt: skip
    o[row, 9], o[row, 10], o[row, 11] = scale(total, 0.25)


@kernel
def bake_glow(geo, surf, mats, world_from_object, shape, material, level, out, stack, lobes):
    """Cut every triangle of mesh shape row `shape` (world_from_object its 4 x 4 matrix) into
    level^2 sub-triangles and write each to a row of `out` (12 columns: world corners 0, 1,
    2, then the mean emission of material row `material` over it); returns the rows
    written. `stack` and `lobes`: the program's scratch (SHADER_STACK, LOBE_COUNT)."""
    mesh = geo.shape_index[shape]
    first = surf.mesh_tri_offset[mesh]
    slots = geo.tri_corners.shape[0] * geo.tri_corners.shape[2]
    end = surf.mesh_tri_offset[mesh + 1] if mesh + 1 < surf.mesh_tri_offset.shape[0] else slots
    step = 1.0 / level
    row = 0
    for slot in range(first, end):
        if math.isnan(_corner(geo.tri_corners, slot, 0)[0]):
            continue  # a leaf's empty slot
        for i in range(level):
            for j in range(level - i):
                # the grid's upward sub-triangle at (i, j), then the downward one beside it
                a, b, c = i * step, (i + 1) * step, j * step
                up = ((a, c), (b, c), (a, c + step))
                _bake_one(geo, surf, mats, world_from_object, shape, material, slot, up, out,
                          row, stack, lobes)  # fmt: skip
                row += 1
                if j < level - 1 - i:
                    down = ((b, c), (b, c + step), (a, c + step))
                    _bake_one(geo, surf, mats, world_from_object, shape, material, slot, down,
                              out, row, stack, lobes)  # fmt: skip
                    row += 1
    return row
