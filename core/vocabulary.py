"""The vocabularies every layer shares, each listed once: the kinds of shape, the CSG
operations and the sampling patterns, by the name the scene model uses and by the code the
kernels read. No imports: the scene model, the kernels, the Lua language and the add-on all
take these from here (mapping their own spellings onto them where they read them).
"""

# Kinds of shape-table row (the kernels' switch, `core.kernels.shapes`)
SHAPE_SPHERE = 0
SHAPE_BOX = 1
SHAPE_CYLINDER = 2
SHAPE_CONE = 3
SHAPE_TORUS = 4
SHAPE_MESH = 5
SHAPE_CSG = 6  # a CSG tree: its operands are rows of their own (core.kernels.csg)

# CSG operations: steps < 0 of a CSG program (`core.kernels.csg`), by the model's names
CSG_UNION, CSG_INTERSECTION, CSG_DIFFERENCE = -1, -2, -3
CSG_OPERATIONS = {"union": CSG_UNION, "intersection": CSG_INTERSECTION,
                  "difference": CSG_DIFFERENCE}  # fmt: skip
# Operands (leaves) of one CSG tree: the kernel's scratch lists are this long, and packing
# and the Lua commands refuse a tree with more (here, so neither imports the kernels)
MAX_OPERANDS = 256

# Where a pixel's n x n camera rays pass: cell centres, a random point per cell, or n x n
# independent random points anywhere in the pixel
PIXEL_GRID, PIXEL_JITTERED, PIXEL_RANDOM = 0, 1, 2
PIXEL_PATTERNS = {"grid": PIXEL_GRID, "jittered": PIXEL_JITTERED, "random": PIXEL_RANDOM}
# Where an area light's N shadow rays end: independent random points, one per equal-area
# cell, or the first N points of the Halton sequence (bases 2, 3), randomly shifted
SHADOW_UNIFORM, SHADOW_STRATIFIED, SHADOW_HALTON = 0, 1, 2
SHADOW_PATTERNS = {"uniform": SHADOW_UNIFORM, "stratified": SHADOW_STRATIFIED,
                   "halton": SHADOW_HALTON}  # fmt: skip

# What a shadow ray does at a refracting surface (glass, Principled Transmission, Refraction
# BSDF): passes it unbent, dimmed by its transparency (the report's rule, a classic ray
# tracer's cheap approximation), or is blocked, as physics has it and Cycles draws it (light
# crosses a refracting surface only along refracted paths: caustics). Transparent BSDF and
# Alpha let shadow rays through under either rule
GLASS_SHADOWS_ATTENUATED, GLASS_SHADOWS_BLOCKED = 0, 1
GLASS_SHADOWS = {"attenuated": GLASS_SHADOWS_ATTENUATED, "blocked": GLASS_SHADOWS_BLOCKED}

# Which Oren-Nayar model a rough diffuse follows (core.kernels.rough_diffuse's ROUGH_*):
# the energy-preserving one (Cycles from 4.3) or Fujii's (before)
ROUGH_DIFFUSE_MODELS = {"EON": 0, "FON": 1}

# The shadow terminator term of a diffuse lit through a bent normal (core.kernels.bent_normal):
# none, Chiang, Li and Burley's (Cycles before 4.5), Conty Estevez, Lecocq and Stein's (from
# 4.5), or only the latter's test that the light and the bent normal are on one side of the
# smooth surface (a material without Bump Map Correction, from 4.5)
TERMINATOR_NONE, TERMINATOR_CHIANG, TERMINATOR_CONTY, TERMINATOR_SIDES = 0, 1, 2, 3
BUMP_TERMINATORS = {"none": TERMINATOR_NONE, "chiang": TERMINATOR_CHIANG,
                    "conty": TERMINATOR_CONTY}  # fmt: skip
# A material's bump rule (core.Material.bump_rule): the render's term, Bump Map Correction
# off, or a bend that is the surface's own displacement (no term)
BUMP_CORRECTED, BUMP_UNCORRECTED, BUMP_DISPLACED = 0, 1, 2
BUMP_RULES = {"corrected": BUMP_CORRECTED, "uncorrected": BUMP_UNCORRECTED,
              "displaced": BUMP_DISPLACED}  # fmt: skip

# How camera rays leave the camera: from the eye through the image plane, or parallel to the
# view from every point of the image plane
PROJECTION_PERSPECTIVE, PROJECTION_ORTHOGRAPHIC = 0, 1
PROJECTIONS = {"perspective": PROJECTION_PERSPECTIVE, "orthographic": PROJECTION_ORTHOGRAPHIC}

# Render passes beside Combined, in the order of their slots in `Frame.pass_offset`
# (`core.passes` says what each holds and how many channels it has)
PASS_NAMES = ("depth", "mist", "normal", "position", "uv", "object_index", "material_index",
              "diffuse_color", "shadow", "environment", "ambient", "diffuse", "specular",
              "reflection", "refraction", "emission", "crypto_object",
              "crypto_material")  # fmt: skip
PASS_SLOT = {name: slot for slot, name in enumerate(PASS_NAMES)}

# Lights in Blender's units (core.model.emitters), one row each of the emitter table, by the
# way their shadow rays are aimed (core.kernels.emitters). A point or spot light with a radius
# is a sphere, or, with Blender's Soft Falloff (and in every Blender before 4.0), a disk of that
# radius turned towards the lit point; a sun's directions fill a cone (Blender 4.0 on) or, as in
# Blender 3.x, a disk one unit away. The kernels test kinds by range: spheres and disks first,
# then panels, then suns
EMITTER_SPHERE, EMITTER_FACING_DISK = 0, 1
EMITTER_RECTANGLE, EMITTER_ELLIPSE = 2, 3
EMITTER_SUN_CONE, EMITTER_SUN_DISK = 4, 5
# An emissive surface lighting the scene (core.compile.glowing): its triangles, sampled by
# area. Kernels test for it first, before the ranges above
EMITTER_MESH = 6
EMITTER_KINDS = {"sphere": EMITTER_SPHERE, "facing_disk": EMITTER_FACING_DISK,
                 "rectangle": EMITTER_RECTANGLE, "ellipse": EMITTER_ELLIPSE,
                 "sun_cone": EMITTER_SUN_CONE, "sun_disk": EMITTER_SUN_DISK,
                 "mesh": EMITTER_MESH}  # fmt: skip
