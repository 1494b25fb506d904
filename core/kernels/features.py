"""The render features a kernel variant may leave out, as Cycles' KERNEL_FEATURE_* bits do.

Each feature is a module constant, `WITH_<NAME>`, that the kernels reading it import and test
before the feature's code: `if WITH_NODES and programmed:`. numba prunes a branch on a
constant before it types the function (its dead-branch pruning reads globals), so a copy of
the kernel compiled with the constant False never types, lowers or optimises what lies
behind it, nor the callees only that code calls. Here every constant is True: the full
kernel, which renders every scene. `core.jit.variants` makes the copies with some of them
False, and `core.compile.features` reads from a packed scene which ones it uses.

A feature left out must change no pixel of a scene that does not use it: the code behind
its constant does nothing for such a scene (tested: tests/core/test_kernel_variants.py
renders a scene of each feature with its variant and with the full kernel).
"""

# A material whose terms a shader program computes per hit (node materials that vary over
# the surface: textures, Fresnel, Layer Weight...; core.kernels.shader_program)
WITH_NODES = True
# Lights in Blender's units lighting shading points (core.kernels.emitters)
WITH_EMITTERS = True
# Those lights seen by reflected and refracted rays (core.kernels.emitters_seen)
WITH_EMITTERS_SEEN = True
# The World's light falling on shading points (core.kernels.environment)
WITH_ENVIRONMENT = True
# Shadow rays crossing surfaces whose transparency varies (core.kernels.shadow_crossing)
WITH_VARYING_SHADOWS = True
# The photon map's light brought by mirrors and glass (core.kernels.caustics)
WITH_CAUSTICS = True
# Render passes beside Combined (core.kernels.pass_record)
WITH_PASSES = True
# Adaptive anti-aliasing (core.kernels.adaptive_tile)
WITH_ADAPTIVE = True
# Rough mirrors and glass spreading rays over their lobe (core.kernels.glossy)
WITH_GLOSSY = True
# A clear coat over a surface (the Principled BSDF's Coat; core.kernels.clear_coat)
WITH_CLEAR_COAT = True
# Light absorbed inside a closed surface, Beer-Lambert (Volume Absorption; core.kernels.absorption)
WITH_ABSORPTION = True
# Light through a surface from its other side (the Translucent BSDF; core.kernels.translucent)
WITH_TRANSLUCENT = True

# The features' names, in the order of their bits in a variant's tag
FEATURES = (
    "nodes",
    "emitters",
    "emitters_seen",
    "environment",
    "varying_shadows",
    "caustics",
    "passes",
    "adaptive",
    "glossy",
    "clear_coat",
    "absorption",
    "translucent",
)


def constant_name(feature: str) -> str:
    """The module constant a feature's code tests: WITH_<NAME>."""
    return "WITH_" + feature.upper()
