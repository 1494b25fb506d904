"""Borrowed arrays: the packed scene with numba's reference counting switched off.

numba reference-counts every array it hands to a function that it does not inline, with an
atomic increment and decrement, even when the callee only reads it. A packed scene holds
some fifty arrays, and a pixel makes a handful of such calls: those atomics measured a third
of the render time on one thread, and worse on two (both threads count the same arrays).

The entry points called from Python (one per tile, or per batch of rays) therefore rebuild
the scene from "borrowed" copies of its arrays: the same data, shape and strides, but no
owner (a null meminfo), which numba's reference counting skips. This is safe because the
Python caller holds the real arrays for the whole call, and no borrowed array is stored or
returned.

A kernel that receives borrowed arrays cannot see that they have no owner, and keeps the
reference counting it would do for owned ones; re-borrowing its arguments at its top (a
copy of a few fields, no memory touched) lets LLVM drop it all. The kernels called per
shading point do so: a shadow ray cast from such a kernel cost 850 ns, 190 ns re-borrowed.
"""

from numba.core import cgutils
from numba.extending import intrinsic

from ..jit import kernel
from .layout import Frame, Geometry, Lights, Materials, PackedScene, Surfaces
from .workspace import CsgScratch, RayStack, Stacks, Workspace


@intrinsic
def borrowed(typingctx, array):
    """The same array without an owner: reference counting passes it by."""

    def codegen(context, builder, signature, args):
        source = context.make_array(array)(context, builder, args[0])
        copy = context.make_array(array)(context, builder)
        for field in ("data", "shape", "strides", "itemsize", "nitems"):
            setattr(copy, field, getattr(source, field))
        copy.parent = cgutils.get_null_value(copy.parent.type)
        copy.meminfo = cgutils.get_null_value(copy.meminfo.type)
        return copy._getvalue()

    return array(array), codegen


@kernel
def borrow_scene(ps):
    f, g, s, m, li = ps
    return PackedScene(borrow_frame(f), borrow_geometry(g), borrow_surfaces(s),
                       borrow_materials(m), borrow_lights(li))  # fmt: skip


@kernel
def borrow_frame(f):
    return Frame(
        borrowed(f.camera),
        borrowed(f.lens),
        borrowed(f.ambient),
        borrowed(f.background),
        borrowed(f.options),
    )


@kernel
def borrow_geometry(g):
    return Geometry(
        borrowed(g.top_bounds),
        borrowed(g.top_info),
        borrowed(g.top_order),
        borrowed(g.shape_kind),
        borrowed(g.shape_object_from_world),
        borrowed(g.shape_param),
        borrowed(g.shape_index),
        borrowed(g.shape_transparency),
        borrowed(g.shape_bounds),
        borrowed(g.mesh_root),
        borrowed(g.node_boxes),
        borrowed(g.node_links),
        borrowed(g.tri_corners),
        borrowed(g.csg_range),
        borrowed(g.csg_program),
    )


@kernel
def borrow_surfaces(s):
    return Surfaces(
        borrowed(s.shape_material),
        borrowed(s.mesh_tri_offset),
        borrowed(s.mesh_normal_offset),
        borrowed(s.mesh_uv_offset),
        borrowed(s.tri_smooth),
        borrowed(s.tri_normal_index),
        borrowed(s.normals),
        borrowed(s.tri_uv_index),
        borrowed(s.uvs),
    )


@kernel
def borrow_materials(m):
    return Materials(
        borrowed(m.diffuse),
        borrowed(m.specular),
        borrowed(m.shininess),
        borrowed(m.reflectivity),
        borrowed(m.transparency),
        borrowed(m.ior),
        borrowed(m.texture),
        borrowed(m.texture_pixels),
        borrowed(m.texture_offset),
        borrowed(m.texture_size),
    )


@kernel
def borrow_lights(li):
    return Lights(
        borrowed(li.point_position),
        borrowed(li.point_intensity),
        borrowed(li.point_attenuation),
        borrowed(li.area_centre),
        borrowed(li.area_edge_u),
        borrowed(li.area_edge_v),
        borrowed(li.area_intensity),
        borrowed(li.area_attenuation),
        borrowed(li.sun_toward),
        borrowed(li.sun_intensity),
    )


@kernel
def borrow_stacks(stacks):
    c = stacks.csg
    return Stacks(
        borrowed(stacks.top),
        borrowed(stacks.top_t),
        borrowed(stacks.mesh),
        borrowed(stacks.mesh_t),
        CsgScratch(
            borrowed(c.span_f),
            borrowed(c.span_i),
            borrowed(c.segments),
            borrowed(c.cross_f),
            borrowed(c.cross_i),
            borrowed(c.stack),
            borrowed(c.overflow),
        ),
        borrowed(stacks.ray_counts),
        borrowed(stacks.pyramid),
        borrowed(stacks.candidates),
        borrowed(stacks.occluder),
        borrowed(stacks.light_targets),
        borrowed(stacks.visibility),
    )


@kernel
def borrow_workspace(ws):
    rays = ws.rays
    return Workspace(
        borrow_stacks(ws.stacks),
        RayStack(
            borrowed(rays.origin),
            borrowed(rays.direction),
            borrowed(rays.weight),
            borrowed(rays.depth),
        ),
        borrowed(ws.cancel),
    )
