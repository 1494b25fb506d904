"""What the add-on exports from Blender 5.0 (the bpy module): tagged primitives where their
meshes sit, Boolean modifiers as CSG, shared meshes, smooth normals and UVs, area lights."""

import sys

import numpy as np
import pytest

import core
from tests.blender.conftest import clear_scene
from tests.support.probe import hits, packed_shapes
from tests.support.rays import rays_towards_origin

pytestmark = pytest.mark.bpy


@pytest.fixture
def empty_scene(bpy_with_whitted):
    bpy = bpy_with_whitted
    scene = clear_scene(bpy)
    scene.render.engine = "WHITTED"
    scene.render.resolution_x = scene.render.resolution_y = 8
    bpy.ops.object.camera_add(location=(0, -10, 0), rotation=(np.pi / 2, 0, 0))
    scene.camera = bpy.context.active_object
    return scene


def exported(bpy, monkeypatch):
    """Render (8x8) and return what the add-on handed to core: (scene, settings, warnings)."""
    export = sys.modules["whitted.export"]
    captured = []
    original = export.convert

    def capture(depsgraph, mesh_cache=None, **options):
        captured.append(original(depsgraph, mesh_cache, **options))
        return captured[-1]

    monkeypatch.setattr(export, "convert", capture)
    bpy.ops.render.render()
    assert captured, "the engine did not export (see the log)"
    return captured[-1]


def add_primitive(bpy, kind, **placement):
    fine = 128
    if kind == "SPHERE":
        bpy.ops.mesh.primitive_uv_sphere_add(segments=fine, ring_count=fine // 2, **placement)
    elif kind == "CUBE":
        bpy.ops.mesh.primitive_cube_add(**placement)
    elif kind == "CYLINDER":
        bpy.ops.mesh.primitive_cylinder_add(vertices=fine, **placement)
    elif kind == "CONE":
        bpy.ops.mesh.primitive_cone_add(vertices=fine, **placement)
    else:
        bpy.ops.mesh.primitive_torus_add(major_segments=fine, minor_segments=fine // 2,
                                         **placement)  # fmt: skip
    return bpy.context.active_object


def view_rays(eye=(4.0, -6.0, 3.0)):
    return rays_towards_origin(eye, 120, 0.35)


def mask(shapes):
    origins, directions = view_rays()
    _, row, _ = hits(packed_shapes(*shapes), origins, directions)
    return row >= 0


def iou(a, b):
    return np.count_nonzero(a & b) / np.count_nonzero(a | b)


@pytest.mark.parametrize("kind", ["SPHERE", "CUBE", "CYLINDER", "CONE", "TORUS"])
def test_a_tagged_primitive_renders_where_its_mesh_sits(empty_scene, monkeypatch, kind):
    bpy = sys.modules["bpy"]
    obj = add_primitive(bpy, kind, location=(0.3, -0.2, 0.1), rotation=(0.4, -0.3, 0.7))
    obj.scale = (1.2, 0.7, 0.9)
    as_mesh, _, _ = exported(bpy, monkeypatch)
    obj.whitted.shape = kind
    as_shape, _, _ = exported(bpy, monkeypatch)
    (mesh,), (shape,) = as_mesh.shapes, as_shape.shapes
    assert isinstance(mesh, core.Mesh) and not isinstance(shape, core.Mesh)
    overlap = iou(mask([mesh]), mask([shape]))
    assert overlap >= 0.99, f"{kind}: IoU {overlap:.4f}"


def test_boolean_modifiers_render_as_exact_csg_and_hidden_cutters_only_cut(
    empty_scene, monkeypatch
):
    bpy = sys.modules["bpy"]
    cutter = add_primitive(bpy, "CYLINDER", location=(0.2, 0, 0), rotation=(np.pi / 2, 0, 0))
    cutter.scale = (0.5, 0.5, 2.0)
    cutter.whitted.shape = "CYLINDER"
    cutter.hide_render = True
    block = add_primitive(bpy, "CUBE", rotation=(0, 0, 0.3))
    block.whitted.shape = "CUBE"
    modifier = block.modifiers.new("Bore", "BOOLEAN")
    modifier.operation = "DIFFERENCE"
    modifier.object = cutter
    scene, _, warnings = exported(bpy, monkeypatch)
    assert warnings == []
    (solid,) = scene.shapes  # the hidden cutter is not rendered on its own
    assert isinstance(solid, core.Csg) and solid.operation == "difference"
    assert isinstance(solid.left, core.Box) and isinstance(solid.right, core.Cylinder)
    # Blender's own Boolean result (the viewport mesh) as the reference
    depsgraph = bpy.context.evaluated_depsgraph_get()
    evaluated = block.evaluated_get(depsgraph)
    reference = sys.modules["whitted.export.mesh"].triangle_mesh(evaluated.data, "ref")
    world = np.array(block.matrix_world)
    overlap = iou(mask([solid]), mask([core.Mesh("ref", mesh=reference, world_from_object=world)]))
    assert overlap >= 0.99, f"IoU {overlap:.4f}"
    origins, directions = view_rays(eye=(0.2, -6.0, 0.0))
    row = hits(packed_shapes(solid), origins, directions)[1].reshape(120, 120)
    assert row[60, 60] < 0  # looking down the bore: the background


def test_linked_duplicates_share_one_triangle_mesh(empty_scene, monkeypatch):
    bpy = sys.modules["bpy"]
    original = add_primitive(bpy, "SPHERE")
    bpy.ops.object.duplicate_move_linked(TRANSFORM_OT_translate={"value": (3, 0, 0)})
    scene, _, _ = exported(bpy, monkeypatch)
    first, second = scene.shapes
    assert first.mesh is second.mesh
    assert not np.allclose(first.world_from_object, second.world_from_object)
    assert original.data.name == first.mesh.name


def test_smooth_faces_corner_normals_and_uvs_are_exported(empty_scene, monkeypatch):
    bpy = sys.modules["bpy"]
    obj = add_primitive(bpy, "SPHERE")
    bpy.ops.object.shade_smooth()
    obj.data.polygons[0].use_smooth = False
    flat_triangles = len(obj.data.polygons[0].vertices) - 2
    scene, _, _ = exported(bpy, monkeypatch)
    mesh = scene.shapes[0].mesh
    assert mesh.smooth.sum() == len(mesh.triangles) - flat_triangles
    normals = mesh.corner_normals
    # Smooth corners carry Blender's vertex normals, within 0.01 of the sphere's radial
    # direction, where the flat face normals are up to 0.025 off it
    corners = mesh.vertices[mesh.triangles]
    radial = corners / np.linalg.norm(corners, axis=2, keepdims=True)
    smooth = mesh.smooth
    np.testing.assert_allclose(normals[smooth], radial[smooth], atol=0.01)
    assert mesh.corner_uvs is not None and mesh.corner_uvs.shape == (len(mesh.triangles), 3, 2)


def test_area_light_edges_follow_the_object_and_its_size(empty_scene, monkeypatch):
    bpy = sys.modules["bpy"]
    bpy.ops.object.light_add(type="AREA", location=(1, 2, 3), rotation=(0, 0, np.pi / 2))
    light = bpy.context.active_object
    light.data.shape = "RECTANGLE"
    light.data.size, light.data.size_y = 2.0, 0.5
    scene, _, _ = exported(bpy, monkeypatch)
    (area,) = scene.lights
    np.testing.assert_allclose(area.centre, (1, 2, 3), atol=1e-6)
    np.testing.assert_allclose(area.edge_u, (0, 2.0, 0), atol=1e-6)
    np.testing.assert_allclose(area.edge_v, (-0.5, 0, 0), atol=1e-6)


def test_bad_blender_input_is_reported_clearly(empty_scene, monkeypatch):
    bpy = sys.modules["bpy"]
    bpy.ops.object.empty_add()
    bpy.context.active_object.whitted.shape = "SPHERE"
    _, _, warnings = exported(bpy, monkeypatch)
    assert any("is an Empty tagged Sphere" in w for w in warnings)
    bpy.ops.object.light_add(type="AREA")
    bpy.context.active_object.data.size = 0.0
    bpy.context.active_object.name = "Flat"
    # The engine reports the error (the bpy module raises it from the operator)
    message = r"Whitted: area light 'Flat': Light Properties > Light > Size: is 0; .* above 0"
    with pytest.raises(RuntimeError, match=message):
        bpy.ops.render.render()
    flat = bpy.data.objects["Flat"]
    flat.data.size, flat.scale = 1.0, (1.0, 0.0, 1.0)
    with pytest.raises(RuntimeError, match=r"'Flat': Object Properties > Transform > Scale"):
        bpy.ops.render.render()
    bpy.data.objects.remove(bpy.data.objects["Flat"])
    bpy.ops.object.light_add(type="SPOT")
    spot = bpy.context.active_object
    spot.name, spot.scale = "Squashed", (1.0, 1.0, 0.0)
    with pytest.raises(RuntimeError, match=r"'Squashed': Object Properties > Transform > Scale"):
        bpy.ops.render.render()
    bpy.data.objects.remove(spot)
    bpy.ops.render.render()  # Blender stays usable


def material_of(bpy, monkeypatch):
    scene, _, _ = exported(bpy, monkeypatch)
    return scene.shapes[0].material


def compiled_material(bpy, monkeypatch):
    """What the kernels read of the first shape's material, by core.Material's field names
    (a node material's graph folded by the compile)."""
    from types import SimpleNamespace

    from core.compile import compile_scene
    from core.compile.materials import folded_row

    scene, settings, _ = exported(bpy, monkeypatch)
    packed = compile_scene(scene, settings).packed
    row = folded_row(packed.materials, int(packed.surfaces.shape_material[0]))
    return SimpleNamespace(**{k: np.asarray(v) if k != "programmed" else v for k, v in row.items()})


def principled(material):
    return next(n for n in material.node_tree.nodes if n.type == "BSDF_PRINCIPLED")


def sphere_with_material(bpy, name):
    """A UV sphere with a new node material `name`: (object, material)."""
    obj = add_primitive(bpy, "SPHERE")
    material = bpy.data.materials.new(name)
    if bpy.app.version < (5, 0, 0):  # 5.0 always uses nodes and deprecates the flag
        material.use_nodes = True
    obj.data.materials.append(material)
    return obj, material


def test_untouched_materials_follow_their_principled_bsdf(empty_scene, monkeypatch):
    """The Principled BSDF read from the Material Output (export/principled.py): a smooth
    metal is a mirror tinted by its base colour, white at grazing; glass refracts with its
    IOR, a rough surface glints; the Whitted panel's own values win when asked."""
    bpy = sys.modules["bpy"]
    _, material = sphere_with_material(bpy, "Chrome")
    bsdf = principled(material)
    bsdf.inputs["Base Color"].default_value = (0.9, 0.6, 0.2, 1.0)
    bsdf.inputs["Metallic"].default_value = 1.0
    bsdf.inputs["Roughness"].default_value = 0.0
    chrome = compiled_material(bpy, monkeypatch)
    assert chrome.reflectivity == pytest.approx(1.0) and chrome.diffuse == pytest.approx((0, 0, 0))
    assert chrome.mirror_colour == pytest.approx((0.9, 0.6, 0.2), abs=1e-6)
    assert chrome.mirror_edge == pytest.approx((1, 1, 1)) and np.all(chrome.specular == 0)
    bsdf.inputs["Metallic"].default_value = 0.0
    bsdf.inputs["Roughness"].default_value = 0.5
    bsdf.inputs["IOR"].default_value = 1.33
    transmission = "Transmission Weight" if bpy.app.version >= (4, 0, 0) else "Transmission"
    bsdf.inputs[transmission].default_value = 1.0
    water = compiled_material(bpy, monkeypatch)
    assert water.transparency == pytest.approx(1.0) and water.inner_ior == pytest.approx(1.33)
    assert water.mirror_sees_lights  # glass stays sharp, lights seen in it
    bsdf.inputs[transmission].default_value = 0.0
    plastic = compiled_material(bpy, monkeypatch)
    # Roughness 0.5: a glint of alpha 0.25 (core.kernels.microfacet), its layer the IOR's
    # (columns: alpha, Beckmann, ..., coat weight, coat IOR), Multiscatter GGX's by default
    assert plastic.gloss[0] == pytest.approx(0.25) and not plastic.mirror_sees_lights
    # (before 4.0: Specular 0.5, an F0 of 0.04, IOR 1.5, and GGX's lobe by default)
    layered = bpy.app.version >= (4, 0, 0)
    assert plastic.gloss[14] == pytest.approx(1.0)
    assert plastic.gloss[15] == pytest.approx(1.33 if layered else 1.5, abs=1e-3)
    assert (plastic.gloss[16] > 0.0) == layered
    bsdf.inputs[transmission].default_value = 1.0
    # Blender 4's Principled tints each crossing by sqrt(base): a solid, by the base
    per_crossing = np.sqrt((0.9, 0.6, 0.2)) if bpy.app.version >= (4, 0, 0) else (0.9, 0.6, 0.2)
    assert water.glass_transmit == pytest.approx(tuple(per_crossing), abs=1e-6)
    material.whitted.use_whitted = True
    material.whitted.reflectivity = 0.25
    material.whitted.inner_ior = 1.7
    own = material_of(bpy, monkeypatch)
    assert own.reflectivity == 0.25 and own.inner_ior == pytest.approx(1.7)
    assert own.diffuse == pytest.approx((0.9, 0.6, 0.2), abs=1e-6)


def test_nodes_whitted_cannot_evaluate_are_named_in_one_warning_per_material(
    empty_scene, monkeypatch
):
    bpy = sys.modules["bpy"]
    _, material = sphere_with_material(bpy, "Marble")
    tree = material.node_tree
    attribute = tree.nodes.new("ShaderNodeAttribute")
    attribute.attribute_type = "OBJECT"  # an object's property: not evaluated (a mesh's is)
    tree.links.new(attribute.outputs["Color"], principled(material).inputs["Base Color"])
    sky = tree.nodes.new("ShaderNodeTexSky")
    tree.links.new(sky.outputs["Color"], principled(material).inputs["Normal"])
    volume = tree.nodes.new("ShaderNodeVolumePrincipled")
    output = next(n for n in tree.nodes if n.type == "OUTPUT_MATERIAL")
    tree.links.new(volume.outputs[0], output.inputs["Volume"])
    scene, _, warnings = exported(bpy, monkeypatch)
    mine = [w for w in warnings if w.startswith("material 'Marble'")]
    assert len(mine) == 1, warnings
    for named in ("'Attribute'", "Base Color", "Normal", "Volume", "used:"):
        assert named in mine[0], mine[0]
    # What was used instead: the Base Color's own value
    base = tuple(principled(material).inputs["Base Color"].default_value[:3])
    assert scene.shapes[0].material.surface.inputs["Base Color"] == pytest.approx(base, abs=1e-6)


def test_an_unmodelled_principled_input_driven_by_a_texture_is_named(empty_scene, monkeypatch):
    """Sheen weight from a texture (as importers link sheen maps) is named with the node
    that drives it, though the socket's own value is the neutral 0; a weight at 0 with
    nothing linked says nothing."""
    bpy = sys.modules["bpy"]
    _, material = sphere_with_material(bpy, "Velvet")
    tree = material.node_tree
    node = principled(material)
    sheen = "Sheen Weight" if node.inputs.get("Sheen Weight") is not None else "Sheen"
    _, _, warnings = exported(bpy, monkeypatch)
    assert not [w for w in warnings if w.startswith("material 'Velvet'")], warnings
    image = tree.nodes.new("ShaderNodeTexImage")
    image.image = bpy.data.images.new("Sheen map", 2, 2)
    tree.links.new(image.outputs["Color"], node.inputs[sheen])
    assert node.inputs[sheen].default_value == 0.0
    _, _, warnings = exported(bpy, monkeypatch)
    mine = [w for w in warnings if w.startswith("material 'Velvet'")]
    assert len(mine) == 1, warnings
    assert f"{sheen}, driven by node 'Image Texture', is not modelled" in mine[0], mine[0]


def test_a_noise_texture_is_read_and_its_other_kinds_are_named(empty_scene, monkeypatch):
    """A 3D fBM Noise is evaluated (no warning); 4D, or a Noise Type other than fBM (4.1
    on), is named in the material's warning with what was used instead."""
    bpy = sys.modules["bpy"]
    _, material = sphere_with_material(bpy, "Clouds")
    noise = material.node_tree.nodes.new("ShaderNodeTexNoise")
    noise.inputs["Detail"].default_value = 4.5
    tree = material.node_tree
    tree.links.new(noise.outputs["Color"], principled(material).inputs["Base Color"])
    scene, _, warnings = exported(bpy, monkeypatch)
    assert not [w for w in warnings if w.startswith("material 'Clouds'")], warnings
    made = scene.shapes[0].material.surface.inputs["Base Color"].node
    assert made.kind == "noise" and made.inputs["Detail"] == pytest.approx(4.5)
    noise.noise_dimensions = "4D"
    if hasattr(noise, "noise_type"):
        noise.noise_type = "RIDGED_MULTIFRACTAL"
    _, _, warnings = exported(bpy, monkeypatch)
    mine = [w for w in warnings if w.startswith("material 'Clouds'")]
    assert len(mine) == 1 and "4D dimensions (used: 3D)" in mine[0], warnings
    if hasattr(noise, "noise_type"):
        assert "Ridged Multifractal type (used: fBM)" in mine[0]


def test_a_voronoi_texture_is_read_with_its_cell_hash_and_its_other_kinds_named(
    empty_scene, monkeypatch
):
    """A 3D F2 Voronoi (Chebychev) is evaluated with the cell hash of this Blender's
    Cycles (lookup3 before 5.0, PCG from 5.0) and no warning; a 2D one, or Distance to
    Edge, is named in the material's warning with what was used instead."""
    bpy = sys.modules["bpy"]
    _, material = sphere_with_material(bpy, "Cells")
    voronoi = material.node_tree.nodes.new("ShaderNodeTexVoronoi")
    voronoi.feature, voronoi.distance = "F2", "CHEBYCHEV"
    voronoi.inputs["Randomness"].default_value = 0.25
    tree = material.node_tree
    tree.links.new(voronoi.outputs["Color"], principled(material).inputs["Base Color"])
    scene, _, warnings = exported(bpy, monkeypatch)
    assert not [w for w in warnings if w.startswith("material 'Cells'")], warnings
    made = scene.shapes[0].material.surface.inputs["Base Color"].node
    assert made.kind == "voronoi" and made.inputs["Randomness"] == pytest.approx(0.25)
    assert (made.settings["feature"], made.settings["distance"]) == ("F2", "CHEBYCHEV")
    expected = "PCG" if bpy.app.version >= (5, 0, 0) else "LOOKUP3"
    assert made.settings["cell_hash"] == expected
    voronoi.voronoi_dimensions = "2D"
    voronoi.feature = "DISTANCE_TO_EDGE"
    _, _, warnings = exported(bpy, monkeypatch)
    mine = [w for w in warnings if w.startswith("material 'Cells'")]
    assert len(mine) == 1 and "2D dimensions (used: 3D)" in mine[0], warnings
    assert "Distance To Edge feature (used: F1)" in mine[0]


def test_a_rough_glass_reads_its_roughness_and_names_a_beckmann_distribution(
    empty_scene, monkeypatch
):
    """A Glass BSDF's Roughness is read (glossy samples spread its rays by GGX); Beckmann,
    Blender's default before 4.0, is kept for its glint and named in the warning, its
    spread rays being GGX's."""
    bpy = sys.modules["bpy"]
    _, material = sphere_with_material(bpy, "Frosted")
    tree = material.node_tree
    glass = tree.nodes.new("ShaderNodeBsdfGlass")
    glass.inputs["Roughness"].default_value = 0.3
    glass.distribution = "GGX"
    output = next(n for n in tree.nodes if n.type == "OUTPUT_MATERIAL")
    tree.links.new(glass.outputs[0], output.inputs["Surface"])
    scene, _, warnings = exported(bpy, monkeypatch)
    assert not [w for w in warnings if w.startswith(f"material '{material.name}'")], warnings
    made = scene.shapes[0].material.surface
    assert made.kind == "glass" and made.inputs["Roughness"] == pytest.approx(0.3)
    glass.distribution = "BECKMANN"
    _, _, warnings = exported(bpy, monkeypatch)
    mine = [w for w in warnings if w.startswith(f"material '{material.name}'")]
    assert len(mine) == 1 and "Beckmann distribution (used: GGX for the rays" in mine[0], warnings
    assert scene.shapes[0].material.surface.settings["distribution"] == "GGX"
    scene, _, _ = exported(bpy, monkeypatch)
    assert scene.shapes[0].material.surface.settings["distribution"] == "BECKMANN"


def test_an_image_texture_on_the_base_colour_is_read_with_its_pixels(empty_scene, monkeypatch):
    bpy = sys.modules["bpy"]
    _, material = sphere_with_material(bpy, "Checker")
    image = bpy.data.images.new("Ramp", 4, 2)
    pixels = np.zeros((2, 4, 4), np.float32)
    pixels[0, :, 0] = 1.0  # Blender's bottom row red
    pixels[1, :, 2] = 1.0  # its top row blue
    pixels[..., 3] = 1.0
    image.pixels.foreach_set(pixels.ravel())
    node = material.node_tree.nodes.new("ShaderNodeTexImage")
    node.image = image
    material.node_tree.links.new(node.outputs["Color"], principled(material).inputs["Base Color"])
    link = material_of(bpy, monkeypatch).surface.inputs["Base Color"]
    texture = link.node.settings["texture"]
    assert link.node.kind == "image" and texture.pixels.shape == (2, 4, 4)
    np.testing.assert_allclose(texture.pixels[0, 0], (0, 0, 1, 1))  # core: top row first
    np.testing.assert_allclose(texture.pixels[1, 0], (1, 0, 0, 1))
    image.filepath = "/nonexistent/missing.png"
    image.source = "FILE"
    with pytest.raises(RuntimeError, match=r"material 'Checker'.*image 'Ramp'.*missing"):
        bpy.ops.render.render()


def test_camera_shift_and_depth_of_field_come_from_blenders_camera(empty_scene, monkeypatch):
    bpy = sys.modules["bpy"]
    scene = empty_scene
    scene.render.resolution_x, scene.render.resolution_y = 40, 30
    camera = scene.camera
    camera.data.shift_x, camera.data.shift_y = 0.2, -0.1
    camera.data.dof.use_dof = True
    camera.data.dof.aperture_fstop = 2.0
    camera.data.lens = 50.0
    add_primitive(bpy, "CUBE", location=(0, 0, 0))
    camera.data.dof.focus_object = bpy.context.active_object
    exported_scene, settings, _ = exported(bpy, monkeypatch)
    cam = exported_scene.camera
    assert cam.aperture_radius == pytest.approx(0.05 / 4.0)
    assert cam.focal_distance == pytest.approx(10.0)
    # The centre of Blender's own camera frame, seen from the camera
    frame = [np.array(corner) for corner in camera.data.view_frame(scene=scene)]
    centre = sum(frame) / 4.0
    half_width = abs(frame[0][0] - frame[2][0]) / 2.0
    half_height = abs(frame[0][1] - frame[2][1]) / 2.0
    expected = (centre[0] / half_width, centre[1] / half_height)
    assert cam.shift == pytest.approx(expected, abs=1e-6)
    scene.whitted.max_depth, scene.whitted.pixel_samples = 9, 3
    scene.whitted.pixel_sampling, scene.whitted.seed = "JITTERED", 7
    _, settings, _ = exported(bpy, monkeypatch)
    assert (settings.max_depth, settings.pixel_samples, settings.pixel_sampling) == (
        9, 3, "jittered",
    )  # fmt: skip
    assert settings.seed == 7


@pytest.mark.parametrize("kind", ["SPHERE", "CUBE", "CYLINDER", "CONE", "TORUS"])
def test_add_menu_creates_a_tagged_stand_in(empty_scene, kind):
    bpy = sys.modules["bpy"]
    assert bpy.ops.whitted.add_shape(shape=kind) == {"FINISHED"}
    obj = bpy.context.active_object
    assert obj.type == "MESH" and obj.whitted.shape == kind and len(obj.data.polygons) > 0


def test_a_sun_shines_along_its_minus_z_with_its_strength_and_angle(empty_scene, monkeypatch):
    bpy = sys.modules["bpy"]
    bpy.ops.object.light_add(type="SUN", rotation=(np.pi / 2, 0, 0))
    sun = bpy.context.active_object.data
    sun.energy, sun.color, sun.angle = 3.0, (1.0, 0.5, 0.25), np.radians(10.0)
    scene, _, warnings = exported(bpy, monkeypatch)
    (light,) = scene.lights
    assert isinstance(light, core.SunLight) and warnings == []
    np.testing.assert_allclose(light.direction, (0, 1.0, 0), atol=1e-6)
    np.testing.assert_allclose(light.irradiance, np.array([1.0, 0.5, 0.25]) * 3.0)
    assert light.angle == pytest.approx(10.0)
    assert light.sampling == ("disk" if bpy.app.version < (4, 0, 0) else "cone")


def test_an_unchanged_mesh_is_not_exported_again_on_the_next_frame(empty_scene, monkeypatch):
    bpy = sys.modules["bpy"]
    obj = add_primitive(bpy, "SPHERE")
    mesh_export = sys.modules["whitted.export.mesh"]
    calls = []
    original = mesh_export.convert

    def counting(mesh, name):
        calls.append(name)
        return original(mesh, name)

    monkeypatch.setattr(mesh_export, "convert", counting)
    first, _, _ = exported(bpy, monkeypatch)
    empty_scene.frame_set(2)
    second, _, _ = exported(bpy, monkeypatch)
    # (none on the first frame when an earlier test left the same sphere in the cache)
    assert len(calls) <= 1 and second.shapes[0].mesh is first.shapes[0].mesh
    converted = len(calls)
    obj.data.vertices[0].co.z += 0.1
    third, _, _ = exported(bpy, monkeypatch)
    assert len(calls) == converted + 1  # the edited mesh, converted again
    assert third.shapes[0].mesh is not first.shapes[0].mesh
    assert third.shapes[0].mesh.vertices[0, 2] == pytest.approx(
        first.shapes[0].mesh.vertices[0, 2] + 0.1
    )


def test_text_and_curves_render_through_their_evaluated_meshes(empty_scene, monkeypatch):
    bpy = sys.modules["bpy"]
    bpy.ops.object.text_add()
    bpy.ops.curve.primitive_bezier_circle_add(location=(0, 0, 2))
    bpy.context.active_object.data.bevel_depth = 0.1
    scene, _, warnings = exported(bpy, monkeypatch)
    assert warnings == [] and len(scene.shapes) == 2
    assert all(isinstance(s, core.Mesh) and len(s.mesh.triangles) > 10 for s in scene.shapes)


def test_spot_and_disk_lights_render_and_what_cannot_be_honoured_is_named(empty_scene, monkeypatch):
    bpy = sys.modules["bpy"]
    bpy.ops.object.light_add(type="SPOT")
    bpy.context.active_object.name = "Stage"
    bpy.ops.object.light_add(type="AREA")
    round_light = bpy.context.active_object
    round_light.data.shape = "DISK"
    round_light.name = "Round"
    scene, _, warnings = exported(bpy, monkeypatch)
    assert warnings == []
    by_name = {light.name: light for light in scene.lights}
    assert isinstance(by_name["Stage"], core.SpotLight)
    assert by_name["Round"].shape == "ellipse"
    round_light.data.spread = np.radians(60.0)
    bpy.ops.object.light_add(type="POINT")
    cs488 = bpy.context.active_object
    cs488.name, cs488.data.whitted.model, cs488.data.shadow_soft_size = "Old", "CS488", 0.5
    # A light's node tree that changes its light (Blender 5.2 gives every light the default)
    stage = bpy.data.objects["Stage"].data
    if stage.node_tree is None:
        stage.use_nodes = True
    emission = next(n for n in stage.node_tree.nodes if n.type == "EMISSION")
    emission.inputs["Strength"].default_value = 2.0
    _, _, warnings = exported(bpy, monkeypatch)
    assert any("'Round'" in w and "Spread 60°" in w for w in warnings)
    assert any("'Old'" in w and "Radius 0.5 m" in w and "Light Model" in w for w in warnings)
    assert any("'Stage'" in w and "shader nodes" in w for w in warnings)
    assert len(warnings) == 3


def test_faces_keep_the_material_of_their_slot(empty_scene, monkeypatch):
    bpy = sys.modules["bpy"]
    obj = add_primitive(bpy, "CUBE")
    for name in ("Paint", "Rust"):
        obj.data.materials.append(bpy.data.materials.new(name))
    obj.data.polygons[0].material_index = 1
    obj.data.polygons[3].material_index = 1
    scene, _, _ = exported(bpy, monkeypatch)
    by_name = {s.material.name: s for s in scene.shapes}
    assert set(by_name) == {"Paint", "Rust"}
    assert len(by_name["Rust"].mesh.triangles) == 4 and len(by_name["Paint"].mesh.triangles) == 8
    # One solid still: the parts share the vertices and a Boolean base stays whole
    assert by_name["Rust"].mesh.vertices is by_name["Paint"].mesh.vertices


def test_boolean_operands_nest_and_collections_cut_as_their_union(empty_scene, monkeypatch):
    bpy = sys.modules["bpy"]
    bead = add_primitive(bpy, "SPHERE", location=(0, 0, 1.0))
    bead.whitted.shape, bead.hide_render = "SPHERE", True
    bead.scale = (0.3, 0.3, 0.3)
    cutter = add_primitive(bpy, "CYLINDER", location=(0, 0, 0))
    cutter.whitted.shape, cutter.hide_render = "CYLINDER", True
    cutter.scale = (0.5, 0.5, 2.0)
    inner = cutter.modifiers.new("Notch", "BOOLEAN")
    inner.operation, inner.object = "DIFFERENCE", bead
    tools = bpy.data.collections.new("Tools")
    bpy.context.scene.collection.children.link(tools)
    for x in (-0.7, 0.7):
        pin = add_primitive(bpy, "CUBE", location=(x, 0, 0))
        pin.whitted.shape, pin.hide_render = "CUBE", True
        pin.scale = (0.1, 0.1, 2.0)
        tools.objects.link(pin)
    block = add_primitive(bpy, "CUBE")
    block.whitted.shape = "CUBE"
    first = block.modifiers.new("Bore", "BOOLEAN")
    first.operation, first.object = "DIFFERENCE", cutter
    second = block.modifiers.new("Pins", "BOOLEAN")
    second.operand_type, second.collection = "COLLECTION", tools
    second.operation = "DIFFERENCE"
    scene, _, _ = exported(bpy, monkeypatch)
    (solid,) = scene.shapes
    assert solid.operation == "difference" and solid.right.operation == "union"
    bored = solid.left
    assert bored.operation == "difference" and isinstance(bored.right, core.Csg)
    assert isinstance(bored.right.right, core.Sphere)  # the cutter's own notch, nested
    # Down the bore the ray meets the bead (a notch left in the cutter: material stays)
    t, row, _ = hits(packed_shapes(solid), np.array([[0.0, 0, 5.0]]), np.array([[0, 0, -1.0]]))
    assert t[0] == pytest.approx(5.0 - 1.0)  # the block's top face inside the notch sphere


def test_custom_split_normals_are_honoured(empty_scene, monkeypatch):
    bpy = sys.modules["bpy"]
    obj = add_primitive(bpy, "SPHERE")
    bpy.ops.object.shade_smooth()
    if bpy.app.version < (4, 1, 0):
        obj.data.use_auto_smooth = True  # custom normals need it before 4.1
    obj.data.normals_split_custom_set([(0.0, 0.0, 1.0)] * len(obj.data.loops))
    scene, _, _ = exported(bpy, monkeypatch)
    normals = scene.shapes[0].mesh.corner_normals.reshape(-1, 3)
    # Blender stores custom normals compressed, to about 1e-4
    np.testing.assert_allclose(normals, np.tile([0, 0, 1.0], (len(normals), 1)), atol=1e-3)


def test_collection_instances_share_the_instanced_mesh(empty_scene, monkeypatch):
    bpy = sys.modules["bpy"]
    props = bpy.data.collections.new("Props")
    bpy.context.scene.collection.children.link(props)
    ball = add_primitive(bpy, "SPHERE")
    for collection in list(ball.users_collection):
        collection.objects.unlink(ball)
    props.objects.link(ball)
    bpy.context.view_layer.layer_collection.children["Props"].exclude = True
    for x in (-3.0, 3.0):
        bpy.ops.object.collection_instance_add(collection="Props", location=(x, 0, 0))
    scene, _, _ = exported(bpy, monkeypatch)
    first, second = scene.shapes
    assert first.mesh is second.mesh
    gap = second.world_from_object[0, 3] - first.world_from_object[0, 3]
    assert abs(gap) == pytest.approx(6.0)


def test_ray_visibility_shadow_off_makes_an_object_cast_no_shadow(empty_scene, monkeypatch):
    """Object > Visibility > Ray Visibility > Shadow: a tagged shape, a plain mesh and a CSG
    solid each export casts_shadows as that box says."""
    bpy = sys.modules["bpy"]
    ball = add_primitive(bpy, "SPHERE", location=(-3, 0, 0))
    ball.whitted.shape = "SPHERE"
    block = add_primitive(bpy, "CUBE", location=(0, 0, 0))
    cube = add_primitive(bpy, "CUBE", location=(3, 0, 0))
    cutter = add_primitive(bpy, "CYLINDER", location=(3, 0, 0), scale=(0.5, 0.5, 2))
    modifier = cube.modifiers.new("Bore", "BOOLEAN")
    modifier.operation, modifier.object = "DIFFERENCE", cutter
    cutter.hide_render = True
    ball.visible_shadow = block.visible_shadow = cube.visible_shadow = False
    scene, _, _ = exported(bpy, monkeypatch)
    casting = {shape.name.split(":")[0]: shape.casts_shadows for shape in scene.shapes}
    assert casting == {"Sphere": False, "Cube": False, "Cube.001": False}, casting
    block.visible_shadow = cube.visible_shadow = True
    scene, _, _ = exported(bpy, monkeypatch)
    casting = {shape.name.split(":")[0]: shape.casts_shadows for shape in scene.shapes}
    assert casting == {"Sphere": False, "Cube": True, "Cube.001": True}, casting


@pytest.mark.parametrize(
    ("node_type", "drawn_as"),
    [
        ("ShaderNodeSubsurfaceScattering", "diffuse"),
        ("ShaderNodeBsdfToon", "diffuse"),
        ("ShaderNodeBsdfHair", "diffuse"),
        ("ShaderNodeBsdfHairPrincipled", "diffuse"),
        ("ShaderNodeBsdfRayPortal", "transparent"),
    ],
)
def test_a_shader_whitted_does_not_model_is_drawn_as_the_nearest_it_does_not_black(
    empty_scene, monkeypatch, node_type, drawn_as
):
    """Subsurface Scattering, Toon, Hair and Ray Portal: drawn as a Diffuse (or Transparent)
    BSDF of their Color, named in the material's warning with what is used instead."""
    bpy = sys.modules["bpy"]
    _, material = sphere_with_material(bpy, "Odd")
    tree = material.node_tree
    try:
        shader = tree.nodes.new(node_type)
    except RuntimeError:
        pytest.skip(f"no {node_type} in this Blender")
    if shader.inputs.get("Color") is not None:
        shader.inputs["Color"].default_value = (0.7, 0.3, 0.1, 1.0)
    output = next(n for n in tree.nodes if n.type == "OUTPUT_MATERIAL")
    tree.links.new(shader.outputs[0], output.inputs["Surface"])
    scene, _, warnings = exported(bpy, monkeypatch)
    mine = [w for w in warnings if w.startswith(f"material '{material.name}'")]
    assert len(mine) == 1 and shader.name in mine[0] and "used:" in mine[0], warnings
    surface = scene.shapes[0].material.surface
    assert surface.kind == drawn_as
    assert surface.inputs["Color"] == pytest.approx((0.7, 0.3, 0.1), abs=1e-6)
