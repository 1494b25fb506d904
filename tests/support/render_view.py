"""What a render of a .blend sees, exported to core without rendering.

A script's `evaluated_depsgraph_get()` is the viewport's depsgraph: it hides what is hidden
in the viewport and shows what is hidden only from renders (Boolean cutters, for one).
Mirroring each object's render visibility into its viewport visibility first makes the
export what `blender -b` renders. Works for every scene of a file, not only the active one.
"""


def export_scenes(bpy, export) -> list:
    """[(Blender scene name, core.Scene, core.RenderSettings)] of every scene of the open
    file, as Whitted's exporter (`export`, the add-on's module) converts them for a render.
    Raises AssertionError on exporter warnings."""
    for obj in bpy.data.objects:
        obj.hide_viewport = obj.hide_render
    exported = []
    for scene in bpy.data.scenes:
        with bpy.context.temp_override(scene=scene, view_layer=scene.view_layers[0]):
            depsgraph = bpy.context.evaluated_depsgraph_get()
            core_scene, settings, warnings = export.convert(depsgraph)
        assert not warnings, f"{scene.name}: {warnings}"
        exported.append((scene.name, core_scene, settings))
    return exported
