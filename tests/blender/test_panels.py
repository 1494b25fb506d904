"""Blender's panels under Whitted: those whose settings the exporter reads are shown (checked
by changing a setting each draws and seeing the export change), those whose settings it
ignores are not, and the Light panel's type row shows once."""

import sys

import numpy as np
import pytest

pytestmark = pytest.mark.bpy


def shown_panels(bpy):
    return {
        name
        for name in dir(bpy.types)
        if "WHITTED" in getattr(getattr(bpy.types, name), "COMPAT_ENGINES", ())
        and not name.startswith("WHITTED_")
    }


def exported(bpy):
    export = sys.modules["whitted.export"]
    return export.convert(bpy.context.evaluated_depsgraph_get())


def test_panels_whose_settings_the_export_reads_are_shown(sample_scene, bpy_with_whitted):
    bpy = bpy_with_whitted
    shown = shown_panels(bpy)
    scene = sample_scene
    camera = scene.camera.data
    ball = next(o for o in scene.objects if o.type == "MESH" and o.whitted.shape == "SPHERE")
    # (panel, a setting it draws, what the export gives for it)
    checks = [
        ("DATA_PT_camera_dof", lambda: setattr(camera.dof, "use_dof", True),
         lambda s, r: s.camera.aperture_radius),
        ("DATA_PT_camera_dof_aperture", lambda: setattr(camera.dof, "aperture_fstop", 0.5),
         lambda s, r: s.camera.aperture_radius),
        ("DATA_PT_lens", lambda: setattr(camera, "lens", 80.0), lambda s, r: s.camera.fovy),
        # Show in > Viewports: a script's depsgraph is the viewport's (Renders, in a render)
        ("OBJECT_PT_visibility", lambda: setattr(ball, "hide_viewport", True),
         lambda s, r: len(s.shapes)),
        ("RENDER_PT_format", lambda: setattr(scene.render, "resolution_x", 100),
         lambda s, r: r.width),
        ("RENDER_PT_frame_range", None, None),  # the frame rendered: Blender's own
        ("RENDER_PT_output", None, None),  # the file written: Blender's own
        ("RENDER_PT_stamp", None, None),  # Output > Metadata, written by Blender
        ("RENDER_PT_color_management", None, None),  # applied by Blender to the result
        ("DATA_PT_uv_texture", None, None),  # the active UV map (test_export)
        ("DATA_PT_mesh_attributes", None, None),
        ("EEVEE_MATERIAL_PT_context_material", None, None),
        ("MATERIAL_PT_preview", None, None),
    ]  # fmt: skip
    for panel, change, read in checks:
        assert panel in shown, f"{panel} is hidden under Whitted"
        if change is None:
            continue
        before = read(*exported(bpy)[:2])
        change()
        after = read(*exported(bpy)[:2])
        assert not np.isclose(before, after), f"{panel}: its setting changed nothing"


def test_panels_whose_settings_whitted_ignores_are_hidden(bpy_with_whitted):
    shown = shown_panels(bpy_with_whitted)
    for panel in ("DATA_PT_EEVEE_light", "DATA_PT_EEVEE_light_distance", "DATA_PT_spot",
                  "RENDER_PT_freestyle", "VIEWLAYER_PT_freestyle", "DATA_PT_lightprobe",
                  "RENDER_PT_stereoscopy", "RENDER_PT_eevee_film", "DATA_PT_light"):  # fmt: skip
        assert panel not in shown, f"{panel} is shown, but Whitted ignores its settings"


def test_one_light_panel_draws_the_type_row(bpy_with_whitted):
    """Blender's Light panel (the type row) and the Area Shape panel are Whitted's own Light
    panel's now: the type row is drawn by one panel only."""
    bpy = bpy_with_whitted
    shown = shown_panels(bpy)
    light_panels = [n for n in shown if n in ("DATA_PT_light", "DATA_PT_EEVEE_light")]
    assert light_panels == []
    assert bpy.types.WHITTED_PT_light.bl_label == "Light"


def test_ray_visibility_is_drawn_under_whitted_and_each_switch_reaches_the_export(
    sample_scene, bpy_with_whitted
):
    """Object › Visibility › Ray Visibility (Blender's own panel has it for Cycles only):
    Whitted's sub-panel draws the four switches the export reads."""
    bpy = bpy_with_whitted
    panel = bpy.types.WHITTED_PT_object_ray_visibility
    assert panel.bl_parent_id == "OBJECT_PT_visibility"
    assert "OBJECT_PT_visibility" in shown_panels(bpy)
    ball = next(o for o in sample_scene.objects if o.type == "MESH" and o.whitted.shape == "SPHERE")
    switches = {
        "visible_camera": "seen_by_camera",
        "visible_glossy": "seen_in_mirrors",
        "visible_transmission": "seen_through_glass",
        "visible_shadow": "casts_shadows",
    }
    for switch, field in switches.items():
        setattr(ball, switch, False)
        shape = next(s for s in exported(bpy)[0].shapes if s.name == ball.name)
        assert getattr(shape, field) is False, switch
        setattr(ball, switch, True)


def test_the_material_panel_offers_emission_lights_only_where_something_emits(bpy_with_whitted):
    bpy = bpy_with_whitted
    nodes = sys.modules["whitted.core.model.shader"]
    material = sys.modules["whitted.export.material"]
    plain = bpy.data.materials.new("Plain")
    if bpy.app.version < (5, 0, 0):
        plain.use_nodes = True
    surface, _, _ = material.read_graph(plain, textures=False)
    assert not nodes.emits(surface)  # a new Principled: black emission, or strength 0
    principled = plain.node_tree.nodes["Principled BSDF"]
    colour = "Emission Color" if "Emission Color" in principled.inputs else "Emission"
    principled.inputs[colour].default_value = (1.0, 0.5, 0.2, 1.0)
    principled.inputs["Emission Strength"].default_value = 2.0
    surface, _, _ = material.read_graph(plain, textures=False)
    assert nodes.emits(surface)


class RecordingLayout:
    """Stands for a panel's layout: records the label of each property drawn (its `text`,
    else the property's own name) and passes as every sub-layout a panel asks for."""

    def __init__(self, labels):
        self.labels = labels
        self.use_property_split = self.use_property_decorate = False
        self.enabled = self.active = True

    def prop(self, data, name, text=None, expand=False, **_):
        label = text if text is not None else data.bl_rna.properties[name].name
        # Split, a label has the left column (or a checkbox's, the right); unsplit, the width
        limit = LONGEST_UNSPLIT_LABEL
        if self.use_property_split:
            checkbox = data.bl_rna.properties[name].type == "BOOLEAN"
            limit = LONGEST_CHECKBOX_LABEL if checkbox else LONGEST_LABEL
        self.labels.append((type(data).__name__, name, label, limit))

    def _inner(self, *args, **kwargs):
        inner = RecordingLayout(self.labels)
        inner.use_property_split = self.use_property_split
        return inner

    row = column = box = split = grid_flow = _inner

    def label(self, *args, **kwargs):
        pass

    template_ID = template_preview = separator = operator = label  # noqa: N815 (Blender's)


def drawn_labels(bpy, panel_name, context):
    labels = []
    panel = getattr(bpy.types, panel_name)
    # The panel's own Python methods (its mixins' too) on a stand-in with the recording layout
    own = {}
    for cls in reversed(panel.__mro__):
        if cls.__module__.split(".")[0] == panel.__module__.split(".")[0]:
            own.update(vars(cls))
    fake = type("Drawn", (), {**own, "layout": RecordingLayout(labels)})()
    panel.draw(fake, context)
    return labels


# A label longer than this is cut ("Soft Shado…") at the Properties editor's default width
# (measured in Blender 3.4's window at 1280 x 800: "Strength" fits; "Quadratic" and "Backgr…"
# are cut)
LONGEST_LABEL = 8
LONGEST_CHECKBOX_LABEL = 9  # beside its box in the right column ("Selecta…" of Selectable)
LONGEST_UNSPLIT_LABEL = 24  # a row of the panel's whole width


def test_whitteds_panels_fit_their_labels_and_tooltips_speak_a_users_words(
    sample_scene, bpy_with_whitted
):
    bpy = bpy_with_whitted
    scene = sample_scene
    ball = next(o for o in scene.objects if o.type == "MESH" and o.whitted.shape == "SPHERE")
    light = next(o for o in scene.objects if o.type == "LIGHT")
    context = type("Context", (), {
        "scene": scene, "world": scene.world, "object": ball, "material": ball.active_material,
        "light": light.data, "view_layer": scene.view_layers[0],
        "region": type("Region", (), {"width": 300})(), "preferences": bpy.context.preferences,
    })()  # fmt: skip
    panels = [name for name in dir(bpy.types) if name.startswith("WHITTED_PT_")]
    assert len(panels) >= 14
    checked = 0
    for name in panels:
        if name in ("WHITTED_PT_passes", "WHITTED_PT_world_preview"):
            continue  # a header only; a preview image
        for owner, prop, label, limit in drawn_labels(bpy, name, context):
            checked += 1
            assert len(label) <= limit, f"{name}: {owner}.{prop} is labelled {label!r}"
    # Every light type under both light models, both World models
    for kind in ("POINT", "SUN", "SPOT", "AREA"):
        for model in ("BLENDER", "CS488"):
            light.data.type, light.data.whitted.model = kind, model
            context.light = light.data
            for owner, prop, label, limit in drawn_labels(bpy, "WHITTED_PT_light", context):
                checked += 1
                assert len(label) <= limit, f"{kind} light: {owner}.{prop} is {label!r}"
    for model in ("BLENDER", "CS488"):
        scene.world.whitted.model = model
        for owner, prop, label, limit in drawn_labels(bpy, "WHITTED_PT_world", context):
            assert len(label) <= limit, f"{model} World: {owner}.{prop} is {label!r}"
    assert checked > 60
    for group in (scene.whitted, scene.world.whitted, ball.active_material.whitted,
                  light.data.whitted, ball.whitted):  # fmt: skip
        for prop in group.bl_rna.properties:
            words = [prop.description] + [
                item.description for item in getattr(prop, "enum_items", [])
            ]
            assert not any("report" in text.lower() for text in words), prop.identifier


def test_the_world_preview_and_the_whole_aperture_are_shown(sample_scene, bpy_with_whitted):
    """World › Preview is there (rendered by Whitted); Camera › Aperture shows Blades,
    Rotation and Ratio, which Whitted now reads (test_cycles_camera)."""
    bpy = bpy_with_whitted
    preview = bpy.types.WHITTED_PT_world_preview
    context = type("Context", (), {"engine": "WHITTED", "world": sample_scene.world})()
    assert preview.bl_context == "world" and preview.poll(context)
    assert "DATA_PT_camera_dof_aperture" in shown_panels(bpy)
    camera = sample_scene.camera
    camera.data.dof.use_dof = True
    lens = exported(bpy)[0].camera
    camera.data.dof.aperture_blades, camera.data.dof.aperture_ratio = 6, 0.5
    camera.data.dof.aperture_rotation = 0.25
    after = exported(bpy)[0].camera
    assert (lens.aperture_blades, lens.aperture_ratio) == (0, 1.0)
    assert (after.aperture_blades, after.aperture_rotation, after.aperture_ratio) == (
        6, pytest.approx(0.25), 0.5
    )  # fmt: skip
