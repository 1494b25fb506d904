"""A hit's material in the integrator's terms (`Surface`), by one of two routes: a node
material whose terms vary over the surface runs its shader program at the hit (the
`nodes` feature, core.kernels.features: a variant without it compiles neither the
interpreter nor the hit's frame); every other material reads its row of the table."""

from ..jit.decorators import inlined_kernel, kernel
from .attributes import READS_ATTRIBUTES, READS_FRAME, put_attributes
from .bent_normal import kept_above
from .features import WITH_NODES
from .shader_program import run_program
from .surface import diffuse_colour, hit_frame, normal_rows
from .surface_terms import table_surface, terms_from_lobes


@kernel
def run_program_at(geo, surf, mats, shape, material, part, p, n_shading, u, v, stack, lobes,
                   ray):  # fmt: skip
    """Run the material's program at a hit on shape row `shape` (part, point p, shading
    normal, texture coordinates u, v), for `ray` (shader_program.path_ray_at, ray_at),
    leaving its lobes in `lobes`: its frame and colour attributes made only if it reads
    them."""
    reads = mats.shader_frame[material]
    hit, across = hit_frame(geo, surf, shape, part, p, n_shading, u, v,
                            (reads & READS_FRAME) != 0)  # fmt: skip
    if reads & READS_ATTRIBUTES:
        put_attributes(geo, surf, shape, part, p, stack)
    rows = normal_rows(geo.shape_object_from_world, shape)
    run_program(mats, material, stack, lobes, hit, across, rows, ray)


@inlined_kernel
def material_at_hit(geo, surf, mats, ws, shape, material, part, p, d, n_geometric, n_shading,
                    u, v, ray, first):  # fmt: skip
    """(the `Surface` at the hit, its shading normal for reflection and refraction, its
    shading normal for the diffuse). They differ where the graph bends the normal (Bump,
    Normal Map): the first is kept from reflecting into the surface (bent_normal), the
    diffuse keeps the bent one, as Cycles corrects only its specular closures. `ray`: what
    the ray is, for Light Path (shader_program.path_ray_at). `first`: the camera ray's hit
    whose passes are recorded (its diffuse colour is needed even under glass)."""
    if WITH_NODES and mats.shader_range[material, 0] >= 0:
        run_program_at(geo, surf, mats, shape, material, part, p, n_shading, u, v,
                       ws.shader_stack, ws.lobes, ray)  # fmt: skip
        here = terms_from_lobes(ws.lobes)
        if here.normal[0] != 0.0 or here.normal[1] != 0.0 or here.normal[2] != 0.0:
            # Bump, Normal Map: the graph's shading normal, kept from reflecting below
            return here, kept_above(n_geometric, d, here.normal), here.normal
        return here, n_shading, n_shading
    kd = (0.0, 0.0, 0.0)
    if mats.transparency[material] < 1.0 or first:
        kd = diffuse_colour(mats, material, u, v)
    return table_surface(mats, material, kd), n_shading, n_shading
