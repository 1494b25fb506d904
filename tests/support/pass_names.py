"""The pass names Cycles and Whitted write into a multilayer EXR for the same view layer, in
the running Blender (the bpy module, or Blender 3.4 through `--python-expr`)."""

from __future__ import annotations

from pathlib import Path

from tests.support.exr import read_exr

# Every pass switch both engines could honour (Whitted's own terms are switched on apart)
SWITCHES = (
    "use_pass_z", "use_pass_mist", "use_pass_normal", "use_pass_position", "use_pass_uv",
    "use_pass_object_index", "use_pass_material_index", "use_pass_diffuse_color",
    "use_pass_shadow", "use_pass_environment", "use_pass_emit",
    "use_pass_cryptomatte_object", "use_pass_cryptomatte_material",
)  # fmt: skip
# Passes only one of the two engines makes, by design: Whitted's terms; Cycles' noisy image
# (written beside Combined when denoising data is kept)
WHITTED_ONLY = {"Whitted Ambient", "Whitted Diffuse", "Whitted Specular", "Whitted Reflection",
                "Whitted Refraction"}  # fmt: skip
CYCLES_ONLY = {"Noisy Image"}
# Cycles dropped its shadow pass after 3.x; Whitted keeps the one EEVEE still writes under
# that name (the switch is the view layer's use_pass_shadow), compared with Cycles' in 3.4
NOT_IN_NEWER_CYCLES = {"Shadow"}


def render_both(bpy, folder) -> dict[str, set[str]]:
    """Render a cube, a light and a camera at 8 x 8 with every pass switch on, once with
    Cycles and once with Whitted; returns each engine's pass names. (Not the factory settings
    read afresh: that would unregister the add-on.)"""
    scene = bpy.context.scene
    for obj in list(bpy.data.objects):
        bpy.data.objects.remove(obj)
    bpy.ops.mesh.primitive_cube_add()
    bpy.ops.object.light_add(type="POINT", location=(4.0, -4.0, 5.0))
    bpy.ops.object.camera_add(location=(7.0, -7.0, 5.0), rotation=(1.1, 0.0, 0.8))
    scene.camera = bpy.context.active_object
    scene.render.resolution_x = scene.render.resolution_y = 8
    scene.render.resolution_percentage = 100
    layer = scene.view_layers[0]
    for switch in SWITCHES:
        setattr(layer, switch, True)
    settings = scene.render.image_settings
    if hasattr(settings, "media_type"):  # Blender 5: multilayer is a kind of media
        settings.media_type = "MULTI_LAYER_IMAGE"
    settings.file_format = "OPEN_EXR_MULTILAYER"
    names = {}
    try:
        names = _render_each(bpy, scene, layer, folder)
    finally:  # the next test's view layer asks for no pass it did not switch on
        for switch in SWITCHES:
            setattr(layer, switch, False)
        layer.whitted.use_pass_terms = False
    return names


def _render_each(bpy, scene, layer, folder) -> dict[str, set[str]]:
    names = {}
    for engine in ("CYCLES", "WHITTED"):
        scene.render.engine = engine
        if engine == "CYCLES":
            scene.cycles.samples = 1
            scene.cycles.use_denoising = False
        else:
            layer.whitted.use_pass_terms = True
        path = Path(folder) / f"{engine.lower()}.exr"
        scene.render.filepath = str(path)
        bpy.ops.render.render(write_still=True)
        channels, _ = read_exr(path)
        names[engine] = {name.split(".")[1] for name in channels}
    return names
