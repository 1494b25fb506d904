"""Which render features (core.kernels.features) a packed scene uses: the kernel variant that
renders it leaves out the rest (core.jit.variants).

Each test reads the packed arrays the kernels read, with the kernels' own condition for
running the feature's code, so a variant without a feature renders the scene to the same
bits as the full kernel (tests/core/test_kernel_variants.py checks it scene by scene).

`expected_features` answers before the scene is packed, from the scene model alone, with
no kernel run: the warm-up compiles that variant while nothing is packed yet. It may name
more features than the packed scene uses (a constant node graph folds into the table), never
fewer; a variant with more features than a scene uses renders it as the full kernel does.
"""

from __future__ import annotations

import numpy as np

from ..kernels.features import FEATURES
from ..kernels.layout import ENVIRONMENT_NONE, PackedScene
from ..kernels.options import (
    OPTION_ENVIRONMENT,
    OPTION_GLOSSY_SAMPLES,
    OPTION_MAX_DEPTH,
    OPTION_PASSES,
    OPTION_PIXEL_SAMPLES,
)
from ..kernels.shader_program import OP_CLEAR_COAT, OP_CLEAR_COAT_AT_NORMAL, OP_TRANSLUCENT
from ..kernels.shadow_log import SHADOW_VARIES
from ..model import Csg, RenderSettings, Scene
from ..model.emitters import Emitter
from ..model.shader import (
    emits,
    has_clear_coat,
    is_rough,
    is_translucent,
    passes_light,
    sends_caustics,
)


def used_features(packed: PackedScene) -> frozenset[str]:
    """The names of the features `packed` uses (FEATURES' names)."""
    frame, geo, mats, lights = packed.frame, packed.geometry, packed.materials, packed.lights
    options = frame.options
    nodes = bool(np.any(mats.shader_range[:, 0] >= 0))
    emitters = lights.emitter_kind.shape[0] > 0
    used = {
        # the integrator runs a material's program where its range starts at a row
        "nodes": nodes,
        "emitters": emitters,
        # seen by rays after a bounce, which only reflecting or refracting surfaces send
        "emitters_seen": emitters and options[OPTION_MAX_DEPTH] > 0 and _may_bounce(mats, nodes),
        "environment": options[OPTION_ENVIRONMENT] != ENVIRONMENT_NONE,
        # a shadow ray lists crossings only of surfaces whose share varies
        "varying_shadows": bool(np.any(geo.shape_transparency == SHADOW_VARIES)),
        "caustics": lights.photon_cells.shape[0] > 0,
        "passes": options[OPTION_PASSES] != 0,
        "adaptive": frame.sampling[0] > 0.0 and options[OPTION_PIXEL_SAMPLES] > 1,
        # spread only by a rough surface: a folded one's roughness, or a program's per hit
        "glossy": options[OPTION_GLOSSY_SAMPLES] > 0
        and (nodes or bool(np.any(mats.roughness > 0.0))),
        # a folded coat's row, or a coat step in a program run per hit
        "clear_coat": bool(np.any(mats.clear_coat[:, 0] > 0.0)) or _programs_coat(mats),
        # a medium to be in: a material that absorbs (core.kernels.absorption)
        "absorption": bool(np.any(mats.absorption > 0.0)),
        # a folded translucent row, or a Translucent step in a program run per hit
        "translucent": bool(np.any(mats.translucent > 0.0)) or _programs_use(mats, OP_TRANSLUCENT),
    }
    return frozenset(name for name in FEATURES if used[name])


def left_out(packed: PackedScene) -> frozenset[str]:
    """The features `packed` does not use: what its kernel variant leaves out."""
    return frozenset(FEATURES) - used_features(packed)


def _programs_coat(mats) -> bool:
    """Whether a program run per hit has a clear coat's step."""
    return _programs_use(mats, OP_CLEAR_COAT, OP_CLEAR_COAT_AT_NORMAL)


def _programs_use(mats, *steps) -> bool:
    """Whether a program run per hit has one of these steps."""
    for first, end in mats.shader_range:
        ops = mats.shader_ops[first:end, 0] if first >= 0 else mats.shader_ops[:0, 0]
        if np.any(np.isin(ops, steps)):
            return True
    return False


def _may_bounce(mats, nodes: bool) -> bool:
    """Whether any material may send a reflected or refracted ray: a mirror, glass, a coat,
    or a program whose terms are known only per hit."""
    return bool(
        nodes
        or np.any(mats.reflectivity > 0.0)
        or np.any(mats.transparency > 0.0)
        or np.any(mats.coat[:, 0] > 0.0)
    )


def expected_features(scene: Scene, settings: RenderSettings) -> frozenset[str]:
    """A superset of the features `scene` packed for `settings` uses, from the model alone."""
    materials = list({id(m): m for m in _materials(scene.shapes)}.values())
    graphs = [m.surface for m in materials if m.surface is not None]
    varying = [graph for graph in graphs if _varies(graph)]
    nodes = bool(varying)
    emitters = any(isinstance(light, Emitter) for light in scene.lights) or any(
        max(m.emission) > 0.0 for m in materials
    ) or any(emits(graph) for graph in graphs)  # fmt: skip
    # what may send light on: a mirror, glass, or a graph with a mirror's or glass's closure
    specular = any(m.reflectivity > 0.0 or m.transparency > 0.0 for m in materials) or any(
        sends_caustics(graph, True, True) for graph in graphs
    )
    used = {
        "nodes": nodes,
        "emitters": emitters,
        "emitters_seen": emitters and settings.max_depth > 0,
        "environment": scene.environment is not None,
        # only a varying graph's share varies over a surface, and only if it can let light
        # through (under either glass-shadow rule: the more that passes, the safe side)
        "varying_shadows": any(passes_light(graph, True) for graph in varying),
        "caustics": bool(settings.caustics) and settings.caustic_photons != 0 and specular,
        "passes": bool(settings.passes),
        "adaptive": settings.adaptive_threshold > 0.0 and settings.pixel_samples > 1,
        "glossy": settings.glossy_samples > 0
        and (nodes or any(m.roughness > 0.0 for m in materials) or any(map(is_rough, graphs))),
        "clear_coat": any(map(has_clear_coat, graphs)),
        "absorption": any(max(m.absorption) > 0.0 for m in materials),
        "translucent": any(max(m.translucent) > 0.0 for m in materials)
        or any(map(is_translucent, graphs)),
    }
    return frozenset(name for name in FEATURES if used[name])


def _materials(shapes):
    """Every material of these shapes and of their CSG operands."""
    for shape in shapes:
        if isinstance(shape, Csg):
            yield from _materials([s for s in (shape.left, shape.right) if s is not None])
        else:
            yield shape.material


def _varies(graph) -> bool:
    """Whether a node graph's program reads the hit (so runs per hit, not folded); a graph
    the compile will refuse counts as varying, the safe side."""
    from ..model.shader import attribute_names
    from .shader_program import ProgramBuilder

    try:
        builder = ProgramBuilder(lambda texture, owner="": 0, attribute_names([graph]))
        return builder.build(graph).varying
    except Exception:
        return True
