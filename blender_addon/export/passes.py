"""View layer -> the passes to render: Blender's own pass switches (View Layer Properties ›
Passes), Whitted's terms, Cryptomatte's levels, and the World's Mist Pass settings.

Each pass Whitted makes is listed once here with the name, channels and type Blender's
Render Layers node and multilayer EXR files know it by (Cycles' names in the running Blender,
`compat.pass_name`, so compositing set-ups made for Cycles find them).
"""

from __future__ import annotations

from typing import NamedTuple

from .. import core
from ..compat import pass_name
from ..core import passes as core_passes


class BlenderPass(NamedTuple):
    core_name: str  # core.passes' name
    name: str  # Blender's, as the Render Layers node shows it
    chan_id: str  # one letter per channel, as register_pass takes it
    kind: str  # 'VALUE', 'VECTOR' or 'COLOR'
    switch: str  # the ViewLayer property that asks for it (or "whitted." + Whitted's own)


PASSES = (
    BlenderPass("depth", "Depth", "Z", "VALUE", "use_pass_z"),
    BlenderPass("mist", "Mist", "Z", "VALUE", "use_pass_mist"),
    BlenderPass("normal", "Normal", "XYZ", "VECTOR", "use_pass_normal"),
    BlenderPass("position", "Position", "XYZ", "VECTOR", "use_pass_position"),
    BlenderPass("uv", "UV", "UVA", "VECTOR", "use_pass_uv"),
    BlenderPass("object_index", pass_name("IndexOB"), "X", "VALUE", "use_pass_object_index"),
    BlenderPass("material_index", pass_name("IndexMA"), "X", "VALUE", "use_pass_material_index"),
    BlenderPass("diffuse_color", pass_name("DiffCol"), "RGB", "COLOR", "use_pass_diffuse_color"),
    BlenderPass("shadow", "Shadow", "RGB", "COLOR", "use_pass_shadow"),
    BlenderPass("environment", pass_name("Env"), "RGB", "COLOR", "use_pass_environment"),
    BlenderPass("ambient", "Whitted Ambient", "RGB", "COLOR", "whitted.use_pass_terms"),
    BlenderPass("diffuse", "Whitted Diffuse", "RGB", "COLOR", "whitted.use_pass_terms"),
    BlenderPass("specular", "Whitted Specular", "RGB", "COLOR", "whitted.use_pass_terms"),
    BlenderPass("reflection", "Whitted Reflection", "RGB", "COLOR", "whitted.use_pass_terms"),
    BlenderPass("refraction", "Whitted Refraction", "RGB", "COLOR", "whitted.use_pass_terms"),
    BlenderPass("emission", pass_name("Emit"), "RGB", "COLOR", "use_pass_emit"),
)
# Cryptomatte: core's pass, Blender's switch and the layer's name after the view layer's
CRYPTO = (
    ("crypto_object", "use_pass_cryptomatte_object", "CryptoObject"),
    ("crypto_material", "use_pass_cryptomatte_material", "CryptoMaterial"),
)


class CryptoPass(NamedTuple):
    core_name: str
    name: str  # e.g. CryptoObject00: ranks 2k and 2k + 1 as (id, coverage, id, coverage)
    first: int  # its first channel in core's pass
    chan_id: str = "RGBA"
    kind: str = "COLOR"


def _switched_on(view_layer, switch: str) -> bool:
    owner = view_layer
    if switch.startswith("whitted."):
        owner, switch = view_layer.whitted, switch.removeprefix("whitted.")
    return bool(getattr(owner, switch, False))


def crypto_levels(view_layer) -> int:
    return int(getattr(view_layer, "pass_cryptomatte_depth", core_passes.DEFAULT_CRYPTO_LEVELS))


def blender_passes(view_layer) -> list:
    """The passes beside Combined that `view_layer` asks for: `BlenderPass`es and, per
    Cryptomatte layer, a `CryptoPass` for each four channels."""
    found = [p for p in PASSES if _switched_on(view_layer, p.switch)]
    levels = crypto_levels(view_layer)
    for core_name, switch, layer in CRYPTO:
        if _switched_on(view_layer, switch):
            count = core_passes.channels(core_name, levels) // 4
            found += [CryptoPass(core_name, f"{layer}{k:02d}", 4 * k) for k in range(count)]
    return found


def core_names(view_layer) -> tuple[str, ...]:
    names = []
    for blender_pass in blender_passes(view_layer):
        if blender_pass.core_name not in names:
            names.append(blender_pass.core_name)
    return tuple(names)


def apply(render: core.RenderSettings, view_layer, world) -> core.RenderSettings:
    """`render` with the view layer's passes and the world's mist settings."""
    render.passes = core_names(view_layer)
    render.crypto_levels = crypto_levels(view_layer)
    mist = getattr(world, "mist_settings", None)
    if mist is not None:
        render.mist_start = float(mist.start)
        render.mist_depth = float(mist.depth)
        render.mist_falloff = mist.falloff
    return render


def crypto_layers(view_layer) -> list[tuple[str, str]]:
    """(core pass, Cryptomatte layer name as compositors see it, e.g. "ViewLayer.CryptoObject")
    for each Cryptomatte layer the view layer makes."""
    return [
        (core_name, f"{view_layer.name}.{layer}")
        for core_name, switch, layer in CRYPTO
        if _switched_on(view_layer, switch)
    ]
