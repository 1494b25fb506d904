"""A material's shader program, run at a hit: Blender's node graph as a flat list of steps
over a small stack of numbers (the idea of Cycles' SVM), built by
core.compile.shader_program.

Each row of Materials.shader_ops is one step: (op, out, a, b, c, d, e, f), the out and input
operands being stack slots (a triple takes three from its slot) or, for settings, plain
integers. A material's constants are copied to the stack's first slots before its steps run.
Value steps compute texture coordinates, textures and colours; closure steps add lobes
(shader_lobes below), each times its weight, a slot that Mix Shader steps split. What the
lobes make of the surface (core.kernels.surface_terms.terms_from_lobes) is Whitted's
model, as the README's table of Blender nodes documents it; rough lobes also glint in
Blender's lights (core.kernels.microfacet).
"""

import math

from ..jit.decorators import kernel
from .blackbody import blackbody_colour
from .facing_values import facing_value
from .microfacet import (
    DIST_BECKMANN,
    DIST_MULTI_GGX,
    dielectric_average,
    f82_dip,
    ggx_albedo_average,
    multiscatter_fresnel,
    schlick_average,
)
from .noise import noise_texture
from .shader_values import (
    brick,
    bright_contrast,
    checker,
    clamp01,
    colour_ramp,
    gamma,
    gradient,
    hue_saturation_value,
    invert,
    luminance,
    magic,
    mapping,
    math_node,
    mix_colour,
    rgb_curves,
)
from .texture_lookup import image_lookup
from .vec import add, cross, dot, normalize, scale, sub
from .vector_math import vector_math
from .voronoi import voronoi_texture
from .wave import wave_texture
from .white_noise import white_noise

# Steps (Materials.shader_ops[:, 0])
OP_COORD = 1  # out, which (COORD_*), where (0 the hit, 1 and 2 a step across: for Bump)
OP_MAPPING = 2  # out, vector, location, rotation, scale, type
OP_IMAGE = 3  # out colour, out alpha, vector, texture, interpolation, extension
OP_CHECKER = 4  # out colour, out fac, vector, colour 1, colour 2, scale
OP_GRADIENT = 5  # out colour, out fac, vector, type
OP_MATH = 6  # out, a, b, c, operation, clamp
OP_MIX = 7  # out, fac, a, b, blend, clamp
OP_INVERT = 8  # out, fac, colour
OP_GAMMA = 9  # out, colour, gamma
OP_BRIGHT = 10  # out, colour, bright, contrast
OP_HSV = 11  # out, hue, saturation, value, fac, colour
OP_RAMP = 12  # out colour, out alpha, fac, first stop, stops, interpolation
OP_SEPARATE = 13  # out x, out y, out z, vector
OP_COMBINE = 14  # out, x, y, z
OP_TO_VALUE = 15  # out, colour: its luminance
OP_SPLIT = 16  # out weight a, out weight b, weight, fac: w (1 - fac), w fac (fac in 0..1)
OP_COPY = 17  # out, a: a triple
OP_AVERAGE = 18  # out, vector: (x + y + z) / 3 (a vector used as a value)
OP_BUMP = 19  # out, height here, height a step along u, along v, strength, distance; f invert
# out, colour, strength, space (NORMAL_MAP_*), the slot of the mesh's tangents (an
# attribute's, core.kernels.attributes) or -1, 1 to make the mapped vector unit before
# Strength mixes it (core.model.shader's strength_mix "UNIT")
OP_NORMAL_MAP = 29
# out colour, out fac, vector, colour 1, colour 2, mortar colour, scale; its next row
# (OP_MORE): mortar size, mortar smooth, bias, brick width, row height, (offset, squash, 0),
# offset frequency * 256 + squash frequency
OP_BRICK = 30
# out colour, out fac, vector, scale, detail, roughness, lacunarity; its next row (OP_MORE):
# distortion, 1 to normalize, 1 if the colour is read
OP_NOISE = 31
# out colour, out distance, out position, vector, scale, detail, roughness; its next row
# (OP_MORE): lacunarity, randomness, exponent, feature + 2 metric + 8 normalize + 16 hash
OP_VORONOI = 32
OP_FACING = 33  # out, IOR or Blend, normal (-1 the surface's), which (facing_values.FACING_*)
OP_VECTOR_MATH = 34  # out vector, out value, a, b, c, scale, operation
# out, fac, colour, first constant (x's range, 1 to extrapolate, the table's RGB rows), rows
OP_CURVES = 35
OP_MAGIC = 36  # out colour, out fac, vector, scale, distortion, depth
# out colour, out fac, vector, scale, distortion, detail; its next row (OP_MORE): detail
# scale, detail roughness, phase, type + 2 bands direction + 8 rings direction + 32 profile
OP_WAVE = 37
OP_WHITE_NOISE = 38  # out colour, out value, vector, w, dimensions
# Closures take their Normal input's slot in the last column (f), or -1 for the surface's
OP_DIFFUSE = 20  # weight, colour, roughness
OP_GLOSSY = 21  # weight, colour, roughness, distribution (microfacet.DIST_*)
OP_METALLIC = 22  # weight, base, edge tint, roughness, distribution
OP_GLASS = 23  # weight, colour, IOR, 1 glass / 0 refraction, roughness, distribution
OP_TRANSPARENT = 24  # weight, colour
OP_EMISSION = 25  # weight, colour, strength
OP_HOLDOUT = 26  # weight
OP_PRINCIPLED = 27  # weight, base, metallic, roughness, IOR, alpha; its next row (OP_MORE):
# transmission, emission colour, emission strength, specular level, tint, layered, distribution
OP_MORE = 28
# The Principled BSDF's Coat, a step after its OP_PRINCIPLED: weight, coat weight, roughness,
# IOR, tint, alpha, and the Coat Normal's slot (f); the layers below dimmed by its mean
# Fresnel over its lobe (Cycles from 4.5), or (AT_NORMAL) by the Fresnel at its normal (4.2)
OP_CLEAR_COAT = 39
OP_CLEAR_COAT_AT_NORMAL = 40
# out colour, out alpha, the stack slot its caller left the attribute's RGBA in
# (core.kernels.attributes: the stack's top rows, attribute k's at attribute_slot(k))
OP_ATTRIBUTE = 41
OP_TRANSLUCENT = 42  # weight, colour, the Normal's slot (f)
OP_BLACKBODY = 43  # out, temperature (kelvin)
# weight, roughness: a Principled BSDF's Diffuse Roughness, a step after its OP_PRINCIPLED
OP_DIFFUSE_ROUGHNESS = 45
# out, size, the slot of the hit's distances to its triangle's edges (an attribute's,
# core.kernels.attributes: three distances and 1, or zeros off a mesh)
OP_WIREFRAME = 44

# Texture coordinates (OP_COORD)
COORD_UV, COORD_GENERATED, COORD_OBJECT, COORD_NORMAL = 0, 1, 2, 3
# What the ray that met the surface is (`ray`, see ray_at): 1 for a camera ray, for a
# shadow ray, its bounces; its direction (3 numbers from RAY_DIRECTION) and 1 where it met
# the surface's back (RAY_BACKFACING), for Fresnel and Layer Weight (OP_FACING); Light
# Path's other outputs: 1 if it last reflected, if it last refracted, if either (a glossy
# ray: every bounce Whitted traces is one), its length from where it left its last
# surface, its reflections, the transparent surfaces it passed, its refractions; and 0
# (a diffuse ray's outputs: Whitted traces none); then where it met the surface (world) and
# the surface's geometric normal there (world, unit, as the surface gives it)
RAY_IS_CAMERA, RAY_IS_SHADOW, RAY_DEPTH, RAY_DIRECTION, RAY_BACKFACING = 0, 1, 2, 3, 6
RAY_IS_REFLECTION, RAY_IS_TRANSMISSION, RAY_IS_GLOSSY, RAY_LENGTH = 7, 8, 9, 10
RAY_GLOSSY_DEPTH, RAY_TRANSPARENT_DEPTH, RAY_TRANSMISSION_DEPTH, RAY_NEVER = 11, 12, 13, 14
RAY_POSITION, RAY_TRUE_NORMAL = 15, 18
RAY_SIZE = 21
# OP_COORD's `which` for ray entry k is COORD_IS_CAMERA + k (Light Path's outputs, Geometry's
# Backfacing)
COORD_IS_CAMERA, COORD_IS_SHADOW, COORD_RAY_DEPTH = 4, 5, 6
# The Geometry node's vectors (OP_COORD, `geometry_vector`): the hit's world position (a
# step across it, for Bump), its shading and geometric normals and the way back along the
# ray, the normals facing the ray as Cycles turns them
COORD_POSITION, COORD_GEOMETRY_NORMAL, COORD_TRUE_NORMAL, COORD_INCOMING = 40, 41, 42, 43
# Normal Map spaces (OP_NORMAL_MAP)
NORMAL_MAP_TANGENT, NORMAL_MAP_OBJECT, NORMAL_MAP_WORLD = 0, 1, 2

# Slots of the lobes a program adds up (Workspace.lobes)
L_DIFFUSE = 0  # RGB
L_MIRROR = 3  # RGB, at normal incidence
L_EDGE = 6  # RGB, at grazing incidence
L_COAT = 9
L_COAT_IOR = 10  # times the coat's weight
L_COAT_HIDES = 11
L_GLASS = 12
L_GLASS_IOR = 13  # times the glass's weight
L_GLASS_REFLECT = 14  # RGB, times the glass's weight
L_GLASS_TRANSMIT = 17  # RGB, times the glass's weight
L_FRESNEL = 20  # refraction_fresnel, times the glass's weight
L_EMISSION = 21  # RGB
L_TRANSPARENT = 24  # RGB
L_HOLDOUT = 27
L_ROUGH = 28  # 1 if a rough lobe's glint stands for the lights in its mirror
L_NORMAL = 29  # world normal times weight, from closures given a Normal
L_NORMAL_WEIGHT = 32
# roughness times weight of the mirror, coat and glass lobes, and their weight (the mean
# roughness their reflected and refracted rays are spread by, when glossy rays are sampled)
L_ROUGHNESS = 33
L_ROUGHNESS_WEIGHT = 34
# The rough lobes' glints (core.kernels.microfacet.Gloss, its sums)
L_GLOSS_NORMAL = 35  # RGB
L_GLOSS_EDGE = 38  # RGB
L_GLOSS_MS_NORMAL = 41  # RGB
L_GLOSS_MS_EDGE = 44  # RGB
L_GLOSS_COAT = 47
L_GLOSS_COAT_IOR = 48  # times the coat's weight
L_GLOSS_COAT_MS = 49
L_GLOSS_ALPHA = 50  # alpha times weight
L_GLOSS_WEIGHT = 51
L_GLOSS_BECKMANN = 52  # the weight of Beckmann lobes
# The clear coats over the surface (core.kernels.surface_terms.ClearCoat, its sums): their
# reflection's weight, the weight of the closures they cover, IOR, roughness, tint, normal
# (each times the reflection's weight)
L_CLEAR = 53
L_CLEAR_COVER = 54
L_CLEAR_IOR = 55
L_CLEAR_ROUGHNESS = 56
L_CLEAR_TINT = 57  # RGB
L_CLEAR_NORMAL = 60  # RGB, from coats given a Coat Normal
L_CLEAR_NORMAL_WEIGHT = 63
L_CLEAR_AT_NORMAL = 64  # the weight of coats dimming by the Fresnel at their normal
# The specular layers' Specular Tint (RGB, times weight): all of them, and the rough ones'
L_COAT_TINT = 65
L_GLOSS_COAT_TINT = 68
# F82's dip below Schlick's curve near grazing (RGB, times weight; microfacet.f82_dip): the
# mirror lobes', and the rough ones'
L_DIP = 71
L_GLOSS_DIP = 74
L_TRANSLUCENT = 77  # RGB: Lambertian transmission (core.kernels.translucent)
L_DIFFUSE_ROUGHNESS = 80  # the diffuse closures' roughness times their weights
L_DIFFUSE_ROUGHNESS_WEIGHT = 81
LOBE_COUNT = 82

# Slots of a program's stack: constants first, then every node output (a triple each); a
# program that reads colour attributes finds them at the top (`attribute_slot`)
SHADER_STACK = 4096


def attribute_slot(k: int) -> int:
    """Where colour attribute k's RGBA lies on the stack (core.kernels.attributes)."""
    return SHADER_STACK - 4 * (k + 1)


# Past this roughness a mirror or coat lobe also glints; below it
# the lobe is a sharp mirror, in which lights are seen (core.kernels.emitters_seen)
SHARP_ROUGHNESS = 0.1
WEIGHT_CUTOFF = 1e-5


@kernel
def _triple(stack, slot):
    return stack[slot], stack[slot + 1], stack[slot + 2]


@kernel
def _put(stack, slot, v):
    stack[slot], stack[slot + 1], stack[slot + 2] = v[0], v[1], v[2]


@kernel
def _add3(lobes, slot, weight, v):
    lobes[slot] += weight * v[0]
    lobes[slot + 1] += weight * v[1]
    lobes[slot + 2] += weight * v[2]


@kernel
def f0_of_ior(ior):
    return ((ior - 1.0) / (ior + 1.0)) ** 2


@kernel
def ior_of_f0(f0):
    root = math.sqrt(min(max(f0, 0.0), 0.9999))
    return (1.0 + root) / (1.0 - root)


@kernel
def _glint_shape(lobes, weight, roughness, distribution):
    lobes[L_GLOSS_ALPHA] += weight * roughness * roughness
    lobes[L_GLOSS_WEIGHT] += weight
    if distribution == DIST_BECKMANN:
        lobes[L_GLOSS_BECKMANN] += weight
    lobes[L_ROUGH] = 1.0


@kernel
def _glint(lobes, weight, normal, edge, roughness, distribution, dip):
    """A rough mirror lobe's glint: Schlick's Fresnel from `normal` to `edge` (the same
    colour, and no Fresnel, for a Glossy BSDF), and under Multiscatter GGX the light its
    microfacets pass on (core.kernels.microfacet; a Glossy BSDF's colour is its Fss, as
    Cycles takes it)."""
    if roughness <= SHARP_ROUGHNESS or weight <= 0.0:
        return
    if max(normal) <= 0.0 and max(edge) <= 0.0:
        return
    _add3(lobes, L_GLOSS_NORMAL, weight, normal)
    _add3(lobes, L_GLOSS_EDGE, weight, edge)
    _add3(lobes, L_GLOSS_DIP, weight, dip)
    _glint_shape(lobes, weight, roughness, distribution)
    if distribution == DIST_MULTI_GGX:
        e_average = ggx_albedo_average(roughness)
        for c in range(3):
            fss = schlick_average(normal[c], edge[c]) - dip[c] / 126.0  # F82's mean: Cycles'
            fms = multiscatter_fresnel(fss, e_average)
            lobes[L_GLOSS_MS_NORMAL + c] += weight * fms * normal[c]
            lobes[L_GLOSS_MS_EDGE + c] += weight * fms * edge[c]


@kernel
def _coat_glint(lobes, weight, ior, roughness, distribution, tint):
    """A rough dielectric layer's glint: the exact Fresnel of its IOR."""
    if roughness <= SHARP_ROUGHNESS or weight <= 0.0:
        return
    lobes[L_GLOSS_COAT] += weight
    _add3(lobes, L_GLOSS_COAT_TINT, weight, tint)
    lobes[L_GLOSS_COAT_IOR] += weight * ior
    _glint_shape(lobes, weight, roughness, distribution)
    if distribution == DIST_MULTI_GGX:
        e_average = ggx_albedo_average(roughness)
        lobes[L_GLOSS_COAT_MS] += weight * multiscatter_fresnel(dielectric_average(ior), e_average)


@kernel
def _roughness(lobes, weight, roughness):
    lobes[L_ROUGHNESS] += weight * roughness
    lobes[L_ROUGHNESS_WEIGHT] += weight


@kernel
def add_mirror(lobes, weight, normal, edge, roughness, distribution, dip):
    _roughness(lobes, weight, roughness)
    _add3(lobes, L_MIRROR, weight, normal)
    _add3(lobes, L_EDGE, weight, edge)
    _add3(lobes, L_DIP, weight, dip)
    _glint(lobes, weight, normal, edge, roughness, distribution, dip)


@kernel
def add_coat(lobes, weight, ior, roughness, hides, distribution, tint):
    _roughness(lobes, weight, roughness)
    lobes[L_COAT] += weight
    lobes[L_COAT_IOR] += weight * ior
    _add3(lobes, L_COAT_TINT, weight, tint)
    if hides:
        lobes[L_COAT_HIDES] = 1.0
    _coat_glint(lobes, weight, ior, roughness, distribution, tint)


@kernel
def add_glass(lobes, weight, ior, reflect, transmit, fresnel, roughness):
    _roughness(lobes, weight, roughness)
    lobes[L_GLASS] += weight
    lobes[L_GLASS_IOR] += weight * ior
    _add3(lobes, L_GLASS_REFLECT, weight, reflect)
    _add3(lobes, L_GLASS_TRANSMIT, weight, transmit)
    lobes[L_FRESNEL] += weight * fresnel


@kernel
def _nonnegative(c):
    return max(c[0], 0.0), max(c[1], 0.0), max(c[2], 0.0)


@kernel
def _principled(lobes, w, base, metallic, roughness, ior, alpha, more):
    """Cycles' Principled BSDF in lobes (the README's table of Blender nodes)."""
    transmission, emission, strength, level, tint, layered, distribution = more
    base = _nonnegative(base)
    clamped = (min(base[0], 1.0), min(base[1], 1.0), min(base[2], 1.0))
    roughness = min(max(roughness, 0.0), 1.0)
    metallic = min(max(metallic, 0.0), 1.0)
    transmission = min(max(transmission, 0.0), 1.0)
    alpha = min(max(alpha, 0.0), 1.0)
    ior = max(ior, 1e-5)
    _add3(lobes, L_TRANSPARENT, w * (1.0 - alpha), (1.0, 1.0, 1.0))
    w *= alpha
    _add3(lobes, L_EMISSION, w * max(strength, 0.0), _nonnegative(emission))
    if layered:
        tint = _nonnegative(tint)
        if metallic > WEIGHT_CUTOFF:  # Cycles' F82 tint, the Specular Tint its tint
            f82 = (min(tint[0], 1.0), min(tint[1], 1.0), min(tint[2], 1.0))
            add_mirror(lobes, w * metallic, clamped, (1.0, 1.0, 1.0), roughness, distribution,
                       f82_dip(clamped, f82))  # fmt: skip
            w *= 1.0 - metallic
        if transmission > WEIGHT_CUTOFF:
            root = (math.sqrt(clamped[0]), math.sqrt(clamped[1]), math.sqrt(clamped[2]))
            add_glass(lobes, w * transmission, ior, tint, root, 1.0, roughness)
            w *= 1.0 - transmission
        f0 = f0_of_ior(ior) * 2.0 * max(level, 0.0)
        if f0 > 0.0 and w > WEIGHT_CUTOFF:
            add_coat(lobes, w, ior_of_f0(f0), roughness, True, distribution, tint)
        _add3(lobes, L_DIFFUSE, w, base)
        return
    # Before Blender 4.0: additive lobes; `level` is Specular, tint[0] the Specular Tint
    specular = max(level, 0.0)
    tint_share = min(max(tint[0], 0.0), 1.0)
    glass = transmission * (1.0 - metallic)
    _add3(lobes, L_DIFFUSE, w * (1.0 - metallic) * (1.0 - transmission), base)
    spec_weight = w * (1.0 - glass)
    if metallic > WEIGHT_CUTOFF:
        add_mirror(lobes, spec_weight * metallic, clamped, (1.0, 1.0, 1.0), roughness,
                   distribution, (0.0, 0.0, 0.0))  # fmt: skip
    if specular > 0.0 and metallic < 1.0:
        add_coat(lobes, spec_weight * (1.0 - metallic), ior_of_f0(0.08 * specular), roughness,
                 False, distribution, (1.0, 1.0, 1.0))  # fmt: skip
    if glass > WEIGHT_CUTOFF:
        reflect = (
            (1.0 - tint_share) + clamped[0] * tint_share,
            (1.0 - tint_share) + clamped[1] * tint_share,
            (1.0 - tint_share) + clamped[2] * tint_share,
        )
        add_glass(lobes, w * glass, ior, reflect, clamped, 1.0, roughness)


@kernel
def _clear_coat(lobes, stack, w, coat, roughness, ior, tint, alpha, normal_slot, at_normal):
    """Cycles' Principled Coat (from Blender 4.0): a GGX dielectric over every other layer
    of the closure (what it does to them is core.kernels.clear_coat's, per ray)."""
    coat = max(coat, 0.0)  # not clamped above: Cycles lets a coat reflect more than once
    cover = w * min(max(alpha, 0.0), 1.0)
    weight = cover * coat
    if weight <= WEIGHT_CUTOFF:
        return
    lobes[L_CLEAR] += weight
    lobes[L_CLEAR_COVER] += cover
    lobes[L_CLEAR_IOR] += weight * max(ior, 1.0)
    lobes[L_CLEAR_ROUGHNESS] += weight * min(max(roughness, 0.0), 1.0)
    _add3(lobes, L_CLEAR_TINT, weight, _nonnegative(tint))
    if at_normal:
        lobes[L_CLEAR_AT_NORMAL] += weight
    if normal_slot >= 0:
        _add3(lobes, L_CLEAR_NORMAL, weight, _triple(stack, normal_slot))
        lobes[L_CLEAR_NORMAL_WEIGHT] += weight


@kernel
def _bump(stack, out, h0, hx, hy, strength, distance, invert, frame):
    """Cycles' bump: the normal tilted by the height's differences over the steps frame[0]
    and frame[1] (world vectors across the surface), frame[2] the normal."""
    dp_x, dp_y, n = frame
    rx = cross(dp_y, n)
    ry = cross(n, dp_x)
    det = dot(dp_x, rx)
    gradient = add(scale(rx, hx - h0), scale(ry, hy - h0))
    distance = -distance if invert else distance
    sign = 1.0 if det >= 0.0 else -1.0
    tilted = normalize(sub(scale(n, abs(det)), scale(gradient, distance * sign)))
    strength = max(strength, 0.0)
    _put(stack, out, normalize(add(scale(tilted, strength), scale(n, 1.0 - strength))))


@kernel
def _normal_map(stack, out, colour, strength, space, frame, normal_rows, tangents, n_object,
                unit_first):  # fmt: skip
    """Cycles' Normal Map: a tangent-space colour (2c - 1 in the frame of the tangent, the
    bitangent and the normal), or an object- or world-space one, mixed with the normal by
    strength. The tangent frame: the mesh's MikkTSpace tangent and bitangent sign at the
    hit (stack slot `tangents`, interpolated over the triangle), with the bitangent
    sign x N x T and the frame turned into world space from object space, as Cycles; where
    the mesh has none (read as 0), the triangle's own UV gradient (`frame`'s steps)."""
    dp_x, dp_y, n = frame
    m = (2.0 * colour[0] - 1.0, 2.0 * colour[1] - 1.0, 2.0 * colour[2] - 1.0)
    tangent = (0.0, 0.0, 0.0)
    if tangents >= 0:
        tangent = _triple(stack, tangents)
    if space == NORMAL_MAP_TANGENT and dot(tangent, tangent) > 0.0:
        bitangent = scale(cross(n_object, tangent), stack[tangents + 3])
        inside = add(add(scale(tangent, m[0]), scale(bitangent, m[1])), scale(n_object, m[2]))
        mapped = (dot(normal_rows[0], inside), dot(normal_rows[1], inside),
                  dot(normal_rows[2], inside))  # fmt: skip
    elif space == NORMAL_MAP_TANGENT:
        mapped = add(add(scale(normalize(dp_x), m[0]), scale(normalize(dp_y), m[1])),
                     scale(n, m[2]))  # fmt: skip
    elif space == NORMAL_MAP_OBJECT:  # normal_rows: the object-to-world normal transform
        mapped = (dot(normal_rows[0], m), dot(normal_rows[1], m), dot(normal_rows[2], m))
    else:
        mapped = normalize(m)
    # Strength mixes the mapped vector as it is, unit or not (a tangent-space colour's 2c - 1
    # is rarely unit), with the normal, as Cycles 4 does for an object whose transform it
    # has applied to the mesh (any object not instanced): measured in 4.2 and 4.5, a tilt
    # 0.78 long at strength 0.8 comes out as Cycles' to 1e-4, 2% off mixed unit. Cycles 3
    # made it unit first (`unit_first`, measured in 3.4)
    if unit_first:
        mapped = normalize(mapped)
    if strength != 1.0:
        mapped = add(n, scale(sub(mapped, n), max(strength, 0.0)))
    _put(stack, out, normalize(mapped))


@kernel
def _add_normal(lobes, stack, weight, slot):
    if slot >= 0:
        _add3(lobes, L_NORMAL, weight, _triple(stack, slot))
        lobes[L_NORMAL_WEIGHT] += weight


@kernel
def ray_at(is_camera, is_shadow, depth, p, d, n_geometric):
    """`ray` for run_program: what the ray o + t d is, having met a surface of geometric
    normal n_geometric at p (a shadow ray's or a photon's: Light Path's other outputs 0)."""
    back = 1.0 if dot(d, n_geometric) > 0.0 else 0.0
    return (is_camera, is_shadow, float(depth), d[0], d[1], d[2], back,
            0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, p[0], p[1], p[2],
            n_geometric[0], n_geometric[1], n_geometric[2])  # fmt: skip


@kernel
def geometry_vector(which, where, frame, ray):
    """The Geometry node's vector `which` (COORD_POSITION...) at the hit (`where` 0) or a
    step across it (1, 2: `frame`'s world steps), from `ray` and `frame`'s normal."""
    back = ray[RAY_BACKFACING] != 0.0
    if which == COORD_POSITION:
        p = (ray[RAY_POSITION], ray[RAY_POSITION + 1], ray[RAY_POSITION + 2])
        return p if where == 0 else add(p, frame[where - 1])
    if which == COORD_INCOMING:
        return -ray[RAY_DIRECTION], -ray[RAY_DIRECTION + 1], -ray[RAY_DIRECTION + 2]
    if which == COORD_TRUE_NORMAL:
        n = (ray[RAY_TRUE_NORMAL], ray[RAY_TRUE_NORMAL + 1], ray[RAY_TRUE_NORMAL + 2])
    else:
        n = frame[2]
    return scale(n, -1.0) if back else n


@kernel
def path_ray_at(depth, p, d, n_geometric, refracted, length, crossed, refractions):
    """`ray` for run_program of a camera ray or its reflected and refracted rays: `depth`
    bounces, the last a refraction if `refracted`, `length` from where it left its last
    surface, `crossed` transparent surfaces passed, `refractions` of its bounces refracted.
    A camera ray stays one through transparent surfaces (as in Cycles: they keep a ray's
    flags), and after its first bounce is a reflection or transmission ray, glossy."""
    back = 1.0 if dot(d, n_geometric) > 0.0 else 0.0
    bounced = depth > 0
    return (
        0.0 if bounced else 1.0, 0.0, float(depth), d[0], d[1], d[2], back,
        1.0 if bounced and not refracted else 0.0, 1.0 if bounced and refracted else 0.0,
        1.0 if bounced else 0.0, length, float(depth - refractions), float(crossed),
        float(refractions), 0.0, p[0], p[1], p[2], n_geometric[0], n_geometric[1],
        n_geometric[2],
    )  # fmt: skip


@kernel
def run_program(mats, material, stack, lobes, hit, frame, normal_rows, ray):
    """Run the material's program with `hit` = the texture coordinates (uv, generated,
    object, normal) at the hit and a step along u and v (core.kernels.surface.hit_frame),
    `frame` = (step along u, step along v, normal) in world space, `normal_rows` the rows
    of the object-to-world normal transform, `ray` = (1 for a camera ray, 1 for a shadow
    ray, its bounces) for Light Path, then its unit direction and 1 if it met the
    surface's back (dot with the geometric normal > 0) for Fresnel and Layer Weight (see
    `ray_at`), leaving its lobes in `lobes` (LOBE_COUNT zeroed first)."""
    lobes[:] = 0.0
    first, end = mats.shader_range[material, 0], mats.shader_range[material, 1]
    c0, c1 = mats.shader_constant_range[material, 0], mats.shader_constant_range[material, 1]
    constants = mats.shader_constants
    for k in range(c1 - c0):
        stack[k] = constants[c0 + k]
    ops = mats.shader_ops
    s = stack
    row = first
    while row < end:
        op, out, a, b = ops[row, 0], ops[row, 1], ops[row, 2], ops[row, 3]
        c, d, e, f = ops[row, 4], ops[row, 5], ops[row, 6], ops[row, 7]
        row += 1
        if op == OP_COORD:
            if a >= COORD_POSITION:
                _put(s, out, geometry_vector(a, b, frame, ray))
            elif a >= COORD_IS_CAMERA:  # a number about the ray, as a triple
                value = ray[a - COORD_IS_CAMERA]
                _put(s, out, (value, value, value))
            else:
                _put(s, out, hit[b][a])
        elif op == OP_ATTRIBUTE:
            _put(s, out, _triple(s, b))
            s[a] = s[b + 3]
        elif op == OP_BUMP:
            _bump(s, out, s[a], s[b], s[c], s[d], s[e], f != 0, frame)
        elif op == OP_NORMAL_MAP:
            _normal_map(s, out, _triple(s, a), s[b], c, frame, normal_rows, d, hit[0][3], e)
        elif op == OP_FACING:
            normal = frame[2] if b < 0 else _triple(s, b)
            towards = (-ray[RAY_DIRECTION], -ray[RAY_DIRECTION + 1], -ray[RAY_DIRECTION + 2])
            s[out] = facing_value(c, s[a], towards, normal, ray[RAY_BACKFACING] != 0.0)
        elif op == OP_MAPPING:
            v = mapping(f, _triple(s, a), _triple(s, b), _triple(s, c), _triple(s, d))
            _put(s, out, v)
        elif op == OP_IMAGE:
            rgb, alpha = image_lookup(mats, c, _triple(s, b), d, e)
            _put(s, out, rgb)
            s[a] = alpha
        elif op == OP_CHECKER:
            fac = checker(_triple(s, b), s[e])
            _put(s, out, _triple(s, c) if fac == 1.0 else _triple(s, d))
            s[a] = fac
        elif op == OP_BRICK:
            m = ops[row]
            row += 1
            shape = _triple(s, m[6])
            tint, mortar = brick(
                scale(_triple(s, b), s[f]), s[m[1]], s[m[2]], s[m[3]], s[m[4]], s[m[5]],
                shape[0], m[7] // 256, shape[1], m[7] % 256,
            )  # fmt: skip
            bricks = _triple(s, c)
            if mortar != 1.0:
                bricks = add(scale(bricks, 1.0 - tint), scale(_triple(s, d), tint))
            _put(s, out, add(scale(bricks, 1.0 - mortar), scale(_triple(s, e), mortar)))
            s[a] = mortar
        elif op == OP_NOISE:
            m_distortion, m_normalize, m_colour = ops[row, 1], ops[row, 2], ops[row, 3]
            row += 1
            point = scale(_triple(s, b), s[c])
            fac, colour = noise_texture(
                point, s[d], s[e], s[f], s[m_distortion], m_normalize != 0, m_colour != 0
            )
            _put(s, out, colour)
            s[a] = fac
        elif op == OP_VORONOI:
            m = ops[row]
            row += 1
            modes = m[4]
            distance, colour, position = voronoi_texture(
                _triple(s, c), s[d], s[e], s[f], s[m[1]], s[m[2]], s[m[3]],
                modes % 4, (modes // 4) % 4, (modes // 16) % 2 != 0, modes // 32, s[m[5]],
            )  # fmt: skip
            _put(s, out, colour)
            s[a] = distance
            _put(s, b, position)
        elif op == OP_WAVE:
            m = ops[row]
            row += 1
            modes = m[4]
            fac = wave_texture(
                scale(_triple(s, b), s[c]), s[d], s[e], s[m[1]], s[m[2]], s[m[3]],
                modes % 2, (modes // 2) % 4, (modes // 8) % 4, modes // 32,
            )  # fmt: skip
            _put(s, out, (fac, fac, fac))
            s[a] = fac
        elif op == OP_WHITE_NOISE:
            value, colour = white_noise(d, _triple(s, b), s[c])
            _put(s, out, colour)
            s[a] = value
        elif op == OP_MAGIC:
            colour = magic(scale(_triple(s, b), s[c]), e, s[d])
            _put(s, out, colour)
            s[a] = (colour[0] + colour[1] + colour[2]) / 3.0
        elif op == OP_GRADIENT:
            fac = gradient(c, _triple(s, b))
            _put(s, out, (fac, fac, fac))
            s[a] = fac
        elif op == OP_MATH:
            value = math_node(d, s[a], s[b], s[c])
            s[out] = min(max(value, 0.0), 1.0) if e else value
        elif op == OP_VECTOR_MATH:
            vector, value = vector_math(f, _triple(s, b), _triple(s, c), _triple(s, d), s[e])
            _put(s, out, vector)
            s[a] = value
        elif op == OP_MIX:
            t = min(max(s[a], 0.0), 1.0)
            mixed = mix_colour(d, t, _triple(s, b), _triple(s, c))
            _put(s, out, clamp01(mixed) if e else mixed)
        elif op == OP_INVERT:
            _put(s, out, invert(s[a], _triple(s, b)))
        elif op == OP_GAMMA:
            _put(s, out, gamma(_triple(s, a), s[b]))
        elif op == OP_BRIGHT:
            _put(s, out, bright_contrast(_triple(s, a), s[b], s[c]))
        elif op == OP_HSV:
            _put(s, out, hue_saturation_value(s[a], s[b], s[c], s[d], _triple(s, e)))
        elif op == OP_CURVES:
            colour = _triple(s, b)
            curved = rgb_curves(s, c, d, colour)
            t = s[a]
            _put(s, out, (colour[0] + (curved[0] - colour[0]) * t,
                          colour[1] + (curved[1] - colour[1]) * t,
                          colour[2] + (curved[2] - colour[2]) * t))  # fmt: skip
        elif op == OP_RAMP:
            rgb, alpha = colour_ramp(s, c, d, e, s[b])
            _put(s, out, rgb)
            s[a] = alpha
        elif op == OP_SEPARATE:
            v = _triple(s, c)
            s[out], s[a], s[b] = v[0], v[1], v[2]
        elif op == OP_COMBINE:
            _put(s, out, (s[a], s[b], s[c]))
        elif op == OP_TO_VALUE:
            s[out] = luminance(_triple(s, a))
        elif op == OP_WIREFRAME:
            # Cycles keeps the half width's square, so a negative Size draws as its size
            half = 0.5 * abs(s[a])
            s[out] = 0.0
            if s[b + 3] != 0.0 and min(s[b], s[b + 1], s[b + 2]) < half:
                s[out] = 1.0
        elif op == OP_BLACKBODY:
            _put(s, out, blackbody_colour(s[a]))
        elif op == OP_AVERAGE:
            v = _triple(s, a)
            s[out] = (v[0] + v[1] + v[2]) / 3.0
        elif op == OP_COPY:
            _put(s, out, _triple(s, a))
        elif op == OP_SPLIT:
            t = min(max(s[c], 0.0), 1.0)
            w = s[b]
            s[out], s[a] = w * (1.0 - t), w * t
        elif op == OP_DIFFUSE:
            _add3(lobes, L_DIFFUSE, s[out], _nonnegative(_triple(s, a)))
            _add_normal(lobes, s, s[out], f)
            lobes[L_DIFFUSE_ROUGHNESS] += s[out] * s[b]
            lobes[L_DIFFUSE_ROUGHNESS_WEIGHT] += s[out]
        elif op == OP_DIFFUSE_ROUGHNESS:
            lobes[L_DIFFUSE_ROUGHNESS] += s[out] * s[a]
            lobes[L_DIFFUSE_ROUGHNESS_WEIGHT] += s[out]
        elif op == OP_TRANSLUCENT:
            _add3(lobes, L_TRANSLUCENT, s[out], _nonnegative(_triple(s, a)))
            _add_normal(lobes, s, s[out], f)
        elif op == OP_GLOSSY:
            tint = _nonnegative(_triple(s, a))
            add_mirror(lobes, s[out], tint, tint, min(max(s[b], 0.0), 1.0), c, (0.0, 0.0, 0.0))
            _add_normal(lobes, s, s[out], f)
        elif op == OP_METALLIC:
            base = clamp01(_triple(s, a))  # Cycles' F82 tint: Base Color, Edge Tint
            add_mirror(lobes, s[out], base, (1.0, 1.0, 1.0), min(max(s[c], 0.0), 1.0), d,
                       f82_dip(base, clamp01(_triple(s, b))))  # fmt: skip
            _add_normal(lobes, s, s[out], f)
        elif op == OP_GLASS:
            tint = _nonnegative(_triple(s, a))
            reflect = tint if c else (0.0, 0.0, 0.0)
            rough = min(max(s[d], 0.0), 1.0)
            add_glass(lobes, s[out], max(s[b], 1e-5), reflect, tint, float(c), rough)
            _add_normal(lobes, s, s[out], f)
        elif op == OP_TRANSPARENT:
            _add3(lobes, L_TRANSPARENT, s[out], clamp01(_triple(s, a)))
        elif op == OP_EMISSION:
            _add3(lobes, L_EMISSION, s[out] * max(s[b], 0.0), _nonnegative(_triple(s, a)))
        elif op == OP_HOLDOUT:
            lobes[L_HOLDOUT] += s[out]
        elif OP_CLEAR_COAT <= op <= OP_CLEAR_COAT_AT_NORMAL:  # the two rules, 39 and 40
            _clear_coat(lobes, s, s[out], s[a], s[b], s[c], _triple(s, d), s[e], f,
                        op == OP_CLEAR_COAT_AT_NORMAL)  # fmt: skip
        elif op == OP_PRINCIPLED:
            _add_normal(lobes, s, s[out], f)
            m_op, m0, m1, m2 = ops[row, 0], ops[row, 1], ops[row, 2], ops[row, 3]
            m3, m4, m5, m6 = ops[row, 4], ops[row, 5], ops[row, 6], ops[row, 7]
            row += 1
            if m_op == OP_MORE:
                more = (s[m0], _triple(s, m1), s[m2], s[m3], _triple(s, m4), m5 != 0, m6)
                _principled(lobes, s[out], _triple(s, a), s[b], s[c], s[d], s[e], more)
