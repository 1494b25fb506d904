"""The layout of the packed scene the kernels read: flat arrays in five groups.

`core.compile` fills these from a `Scene`. Every array has a fixed dtype and rank whatever
the scene, and `core.compile.kernel_ready` makes every one C-contiguous, aligned and writable,
so the kernels compile once and load from the cache for every scene after.
"""

from typing import NamedTuple

import numpy as np


class Frame(NamedTuple):
    """Camera and render options: what frames the picture."""

    # rows: eye, forward, right and up. Perspective: forward is the ray through the image
    # centre (one unit along the view), right and up are scaled by the half-width and
    # half-height of the image plane at distance 1. Orthographic: the eye is the image
    # centre, forward is the unit view direction, right and up are scaled by the image's
    # half-width and half-height in scene units
    camera: np.ndarray  # float64 (4, 3)
    # float64 (5,): aperture radius, focal distance, blades (0: a disk), rotation, 1 / ratio
    lens: np.ndarray
    ambient: np.ndarray  # float64 (3,)
    background: np.ndarray  # float64 (3,)
    options: np.ndarray  # int64 (OPTION_COUNT,)
    # where each pass (core.passes, in slot order) starts after the pixel's RGBA, or -1
    pass_offset: np.ndarray  # int64 (PASS_COUNT,)
    mist: np.ndarray  # float64 (3,): start, 1 / depth (0 for depth 0), falloff power
    # float64 (1,): adaptive anti-aliasing's threshold, 0 for none (core.kernels.adaptive_tile)
    sampling: np.ndarray


class Geometry(NamedTuple):
    """What rays are traced against: shapes, the top-level BVH, mesh BVHs and triangles."""

    # top-level BVH over shapes, world space (see core.kernels.bvh_build)
    top_bounds: np.ndarray  # float64 (k, 6): lo xyz, hi xyz
    top_info: np.ndarray  # int32 (k, 2)
    top_order: np.ndarray  # int32 (n,): shapes in leaf order
    # shapes: the scene's, then the operands of its CSG trees (which the top level skips)
    shape_kind: np.ndarray  # int32 (n,)
    shape_object_from_world: np.ndarray  # float64 (n, 3, 4): affine rows, inverse transform
    shape_param: np.ndarray  # float64 (n, 2): torus major and minor radius
    shape_index: np.ndarray  # int32 (n,): row in mesh_root (meshes), csg_range (CSG), or -1
    # float64 (n,): what one crossing of its surface lets a shadow ray through: its material's
    # transparency, or 1 (the row is skipped) when it casts no shadow; a CSG row's is 0;
    # SHADOW_VARIES where its program answers each crossing (core.kernels.shadow_log)
    shape_transparency: np.ndarray
    # float64 (n, 3): the colour of that share, as powers: a shadow ray crossing the surface
    # n times gets share^n in all, and per channel share^(n p) = colour^n (core.kernels.trace
    # `tint_by`); 1 for a grey share (and for CSG and varying rows, whose shares are grey)
    shape_shadow_power: np.ndarray
    shape_bounds: np.ndarray  # float64 (n, 6): world box (lo xyz, hi xyz), for CSG operands
    # meshes
    mesh_root: np.ndarray  # int32 (m,): its BVH's root in node_*
    # eight-wide BVH nodes of all meshes (see core.kernels.bvh_wide), global indices
    node_boxes: np.ndarray  # float32 (nodes, 6, 8): lo xyz, hi xyz rows, a column per child
    node_links: np.ndarray  # int32 (nodes, 8): child node, or ~(leaf block << 3 | count)
    # object-space corners, four triangles a BVH leaf (see core.kernels.triangles): rows
    # x y z of corners 0, 1, 2, a column per slot; a triangle is named by its slot
    tri_corners: np.ndarray  # float32 (blocks, 9, 4)
    # CSG trees as postfix programs (see core.kernels.csg): a step >= 0 pushes the spans of
    # that shape row, CSG_UNION / CSG_INTERSECTION / CSG_DIFFERENCE combine the top two
    csg_range: np.ndarray  # int32 (c, 2): first and end step of each tree's program
    csg_program: np.ndarray  # int32 (steps,)


class Surfaces(NamedTuple):
    """What a hit needs beyond geometry: materials of shapes, mesh normals and UVs."""

    shape_material: np.ndarray  # int32 (n,): row in Materials
    mesh_tri_offset: np.ndarray  # int64 (m,): its first triangle slot in tri_*
    mesh_normal_offset: np.ndarray  # int64 (m,): its first row in tri_normal_index, or -1
    mesh_uv_offset: np.ndarray  # int64 (m,): its first row in tri_uv_index, or -1
    tri_smooth: np.ndarray  # uint8 (slots,): 1 if the face is smooth shaded
    tri_normal_index: np.ndarray  # int32 (rows, 3): rows of normals per corner
    normals: np.ndarray  # float32 (r, 3)
    tri_uv_index: np.ndarray  # int32 (rows, 3): rows of uvs per corner
    uvs: np.ndarray  # float32 (r, 2)
    # colour attributes (core.kernels.attributes): per mesh, for each name the programs
    # read, its first row in tri_color_index or -1; the rows of colours per corner; RGBA
    mesh_color_offset: np.ndarray  # int64 (m, names)
    tri_color_index: np.ndarray  # int32 (rows, 3)
    colors: np.ndarray  # float32 (r, 4)
    # per row, of the scene shape it belongs to (a CSG operand: its tree's top node)
    shape_pass_index: np.ndarray  # int32 (n,): the object index pass's value
    shape_holdout: np.ndarray  # uint8 (n,): 1 if camera rays see a hole there
    shape_crypto: np.ndarray  # float32 (n,): the Cryptomatte id of its name
    # uint8 (n,): VISIBLE_* bits, the rays that see it (Object > Visibility > Ray Visibility)
    shape_visibility: np.ndarray
    # float64 (n, 6): its texture space, centre xyz and half size xyz in object space
    # (Blender's Generated coordinates map it to [0, 1])
    shape_texspace: np.ndarray


class Materials(NamedTuple):
    diffuse: np.ndarray  # float64 (q, 3)
    specular: np.ndarray  # float64 (q, 3)
    shininess: np.ndarray  # float64 (q,)
    reflectivity: np.ndarray  # float64 (q,)
    transparency: np.ndarray  # float64 (q,)
    ior: np.ndarray  # float64 (q, 2): outer, inner
    texture: np.ndarray  # int32 (q,): row in texture_*, or -1
    texture_pixels: np.ndarray  # float32 (texels, 3): all images, row-major, top row first
    texture_offset: np.ndarray  # int64 (x,): each image's first texel
    texture_size: np.ndarray  # int64 (x, 2): width, height
    pass_index: np.ndarray  # int32 (q,): the material index pass's value
    crypto: np.ndarray  # float32 (q,): the Cryptomatte id of its name
    # what Blender's node materials add (core.model.Material; core.kernels.integrator)
    mirror: np.ndarray  # float64 (q, 2, 3): the mirror's tint at normal and grazing incidence
    # float64 (q, 6): clear layer's weight, its IOR, 1 if it hides the diffuse, its Specular
    # Tint (RGB)
    coat: np.ndarray
    glass_tint: np.ndarray  # float64 (q, 2, 3): the dielectric's reflection, transmission tint
    refraction_fresnel: np.ndarray  # float64 (q,): 1 glass, 0 all refracts (Refraction BSDF)
    mirror_hides_lights: np.ndarray  # uint8 (q,): 1 if its highlight holds the lights instead
    texture_alpha: np.ndarray  # float32 (texels,): each texel's alpha
    # shader programs (core.kernels.shader_program): rows [first, end) of shader_ops and of
    # shader_constants per material; first -1: none (its terms are the table's)
    shader_range: np.ndarray  # int64 (q, 2)
    shader_constant_range: np.ndarray  # int64 (q, 2)
    shader_ops: np.ndarray  # int32 (steps, 8)
    shader_constants: np.ndarray  # float64 (c,)
    # uint8 (q,): what its program reads beyond the hit's own coordinates, bits
    # (core.kernels.attributes): READS_FRAME the surface's frame and the steps across it
    # (Bump, Normal Map), READS_ATTRIBUTES colour attributes
    shader_frame: np.ndarray
    emission: np.ndarray  # float64 (q, 3): emitted radiance
    transparent: np.ndarray  # float64 (q, 3): share passing straight through
    holdout: np.ndarray  # float64 (q,): share of a camera ray's pixel cut out
    roughness: np.ndarray  # float64 (q,): the mirror's and glass's (core.model.Material)
    # float64 (q, GLOSS_COLUMNS): its rough lobes' glints (core.kernels.surface_terms), zero
    # for the report's materials (their highlight is Phong's: specular, shininess)
    gloss: np.ndarray
    # float64 (q, CLEAR_COAT_COLUMNS): its clear coat (core.kernels.surface_terms), weight 0:
    # none
    clear_coat: np.ndarray
    # float64 (q, 3): F82's dip below the mirror's Schlick curve (core.kernels.microfacet.f82_dip)
    mirror_dip: np.ndarray
    # float64 (q, 3): the absorption coefficient of the medium inside (core.kernels.absorption)
    absorption: np.ndarray
    # float64 (q, 3): Lambertian transmission (core.kernels.translucent)
    translucent: np.ndarray
    # float64 (q,): the diffuse's Oren-Nayar roughness (core.kernels.rough_diffuse)
    diffuse_roughness: np.ndarray
    # uint8 (q,): BUMP_* (core.vocabulary): how its bent normals meet the terminator term
    bump_rule: np.ndarray


class Lights(NamedTuple):
    point_position: np.ndarray  # float64 (l, 3)
    point_intensity: np.ndarray  # float64 (l, 3)
    point_attenuation: np.ndarray  # float64 (l, 3): c0, c1, c2
    area_centre: np.ndarray  # float64 (a, 3)
    area_edge_u: np.ndarray  # float64 (a, 3)
    area_edge_v: np.ndarray  # float64 (a, 3)
    area_intensity: np.ndarray  # float64 (a, 3)
    area_attenuation: np.ndarray  # float64 (a, 3)
    sun_toward: np.ndarray  # float64 (s, 3): unit vector towards a directional light
    sun_intensity: np.ndarray  # float64 (s, 3)
    # lights in Blender's units (core.model.emitters), a row each (core.kernels.emitters)
    emitter_kind: np.ndarray  # int32 (e,): EMITTER_* (core.vocabulary)
    emitter_flags: np.ndarray  # int32 (e,): EMITS_* bits
    emitter_position: np.ndarray  # float64 (e, 3): position, centre, or unit vector to a sun
    # float64 (e, 3, 3): a panel's edge_u, edge_v and unit emitting normal; a spot light's
    # world-to-light rows
    emitter_frame: np.ndarray
    # float64 (e, 4): a sphere's radius, a spot's cos of its half angle and the width of its
    # blend in cos; a sun's 1 - cos and tan of its half angle
    emitter_param: np.ndarray
    emitter_radiance: np.ndarray  # float64 (e, 3): see core.kernels.emitters
    # emissive surfaces as lights (EMITTER_MESH rows; emitter_param: first sub-triangle,
    # triangles, total area times strength, level: core.kernels.light_mesh): world-space
    # corners of each sub-triangle (level^2 a triangle, in the order of core.kernels.glow_bake)
    glow_triangles: np.ndarray  # float64 (t, 9)
    # running shares (light_mesh's SUB_SHARES, ROW_SHARES, TRIANGLE_SHARES): column 0 per
    # sub-triangle, column 1 per row of a triangle's grid, column 2 per triangle, each from
    # its emitter's first row
    glow_cdf: np.ndarray  # float64 (t, 3)
    # each sub-triangle's colour, times the row's radiance (1 for a constant emitter; a
    # varying one's radiance over its strength)
    glow_tint: np.ndarray  # float64 (t, 3)
    # the environment (core.compile.environment, core.kernels.environment); its kind is
    # OPTION_ENVIRONMENT
    env_colour: np.ndarray  # float64 (3,): the uniform radiance, or the image's tint
    env_transform: np.ndarray  # float64 (3, 4): affine rows, view direction -> lookup direction
    env_pixels: np.ndarray  # float32 (width x height, 3): linear RGB, row 0 at the top
    env_size: np.ndarray  # int64 (3,): width, height, 1 if env_transform is a rotation
    env_row_cdf: np.ndarray  # float64 (height + 1,): picks a row
    env_column_cdf: np.ndarray  # float64 (height, width + 1): picks a pixel of the row
    # caustic photons (core.kernels.photons, core.compile.caustics), ordered by their
    # bucket (core.kernels.caustics): where each was stored, its direction of travel, its
    # power (W) and the radius of its disk; the first photon of each bucket (one past the
    # last: the count); the levels' cell edges
    photon_position: np.ndarray  # float64 (m, 3)
    photon_direction: np.ndarray  # float64 (m, 3)
    photon_power: np.ndarray  # float64 (m, 3)
    photon_radius: np.ndarray  # float64 (m,)
    photon_cells: np.ndarray  # int64 (2^b + 1,), or (0,) without photons
    photon_levels: np.ndarray  # float64 (levels,)


# EMITS_* bits of Lights.emitter_flags
EMITS_SHADOW = 1  # casts shadows
EMITS_DIFFUSE = 2  # lights diffuse surfaces
EMITS_SPECULAR = 4  # makes highlights
EMITS_SPOT = 8  # masked to a cone (a spot light)
EMITS_SPOT_COSINE = 16  # and scaled by the cosine from its axis (Blender before 4.0)
EMITS_TRANSMISSION = 32  # seen through glass (its Ray Visibility > Transmission)
EMITS_FROM_SURFACE = 64  # an emissive surface of the scene: shadow rays stop short of it


class PackedScene(NamedTuple):
    """Struct of arrays, in groups. Row i of every `shape_*` array describes shape i, etc.

    Kernels take only the groups they read: numba passes a tuple of arrays field by field,
    on the stack, and reference-counts every array, so handing the whole scene to each
    helper cost more than the tracing itself (measured: three quarters of the render time).
    """

    frame: Frame  # (not "view": numba reserves that attribute name for arrays)
    geometry: Geometry
    surfaces: Surfaces
    materials: Materials
    lights: Lights


# VISIBLE_* bits of Surfaces.shape_visibility: the rays that stop at a shape (the others pass
# through it, as Cycles' Ray Visibility switches do)
VISIBLE_CAMERA = 1
VISIBLE_GLOSSY = 2  # reflected rays
VISIBLE_TRANSMISSION = 4  # refracted rays
VISIBLE_ALL = 7

# OPTION_ENVIRONMENT: what lies beyond the scene
ENVIRONMENT_NONE = 0  # the background colour only (Frame.background), lighting nothing
ENVIRONMENT_UNIFORM = 1  # light of env_colour from every direction
ENVIRONMENT_IMAGE = 2  # an equirectangular image times env_colour
