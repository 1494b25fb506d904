"""CS488 Lua scenes: every command builds what the report describes.

Accuracy is checked against closed forms written here: where rays meet the report's y-up
shapes, the transforms as matrices multiplied by hand, a point light's irradiance on a plane,
and the report's own printed summary of gr.render.
"""

import math
from pathlib import Path

import numpy as np
import pytest
from PIL import Image

import core
from core.compile import pack_scene
from core.cs488 import load_script
from tests.support.probe import hits

SCENES = Path(__file__).resolve().parents[2] / "cs488_scenes"


def load(tmp_path, source, name="scene.lua"):
    script = tmp_path / name
    script.write_text(source)
    printed = []
    calls = load_script(script, print_line=printed.append)
    return calls, printed


def render_call(root="root", lights="{}", size=(8, 8), camera=None, ambient="{0.3, 0.3, 0.3}"):
    eye, view, up = camera or ("{0, 0, 20}", "{0, 0, -1}", "{0, 1, 0}")
    width, height = size
    return (
        f"gr.render({root}, 'out.png', {width}, {height}, {eye}, {view}, {up}, 50, {ambient}, "
        f"{lights})\n"
    )


def test_every_command_builds_its_scene():
    calls = load_script(SCENES / "every_command.lua", print_line=lambda line: None)
    (call,) = calls
    kinds = [type(shape).__name__ for shape in call.scene.shapes]
    assert sorted(kinds) == sorted(
        ["Sphere", "Box", "Cylinder", "Cone", "Torus"] * 2
        + ["Mesh", "Mesh", "Csg", "Csg", "Sphere", "Box"]
    )
    materials = {shape.name: shape.material for shape in call.scene.shapes}
    assert materials["sphere"].texture.srgb is False  # the report's raw texture values
    assert materials["obj box"].reflectivity == 0.6
    assert (materials["cylinder"].outer_ior, materials["cylinder"].inner_ior) == (1.0, 1.0)
    assert materials["cylinder"].transparency == 0.0
    glass = materials["glass ball"]
    assert (glass.transparency, glass.outer_ior, glass.inner_ior) == (1.0, 1.0, 1.53)
    point, area = call.scene.lights
    assert isinstance(point, core.PointLight) and isinstance(area, core.AreaLight)
    assert area.edge_u == (4.0, 0.0, 0.0) and area.edge_v == (0.0, 0.0, -3.0)
    settings, camera = call.settings, call.scene.camera
    assert (settings.max_depth, settings.pixel_samples, settings.shadow_samples) == (4, 3, 4)
    assert (camera.focal_distance, camera.aperture_radius) == (14.0, 0.02)
    assert call.output == SCENES / "every_command.png"
    assert call.warnings == []


def test_the_shorter_render_forms_take_the_reports_defaults(tmp_path):
    source = (
        "root = gr.node('root')\n"
        + render_call()
        + (
            "gr.render(root, 'b.png', 8, 8, {0, 0, 20}, {0, 0, -1}, {0, 1, 0}, 50, {0, 0, 0}, {}, "
            "7, 0, 5)\n"
        )
    )
    (short, middle), _ = load(tmp_path, source)
    assert (short.settings.pixel_samples, short.settings.shadow_samples) == (1, 1)
    assert short.settings.max_depth == core.RenderSettings().max_depth
    assert short.scene.camera.aperture_radius == 0.0
    assert (middle.settings.max_depth, middle.settings.pixel_samples) == (7, 1)
    assert middle.settings.shadow_samples == 5


# Where a ray along -z (or -y) first meets each report shape, in closed form.
def _sphere(c, r, x, y):
    d2 = (x - c[0]) ** 2 + (y - c[1]) ** 2
    return np.where(d2 < r * r, c[2] + np.sqrt(np.maximum(r * r - d2, 0)), np.nan)


def _box(corner, size, x, y):
    inside = (x > corner[0]) & (x < corner[0] + size) & (y > corner[1]) & (y < corner[1] + size)
    return np.where(inside, corner[2] + size, np.nan)


def _cylinder(c, r, h, x, y):
    inside = (np.abs(x - c[0]) < r) & (np.abs(y - c[1]) < h / 2)
    return np.where(inside, c[2] + np.sqrt(np.maximum(r * r - (x - c[0]) ** 2, 0)), np.nan)


def _cone(c, r, h, x, y):
    rho = r * (y - c[1]) / h  # apex at the centre, base of radius r at height h
    inside = (y > c[1]) & (y < c[1] + h) & (np.abs(x - c[0]) < rho)
    return np.where(inside, c[2] + np.sqrt(np.maximum(rho * rho - (x - c[0]) ** 2, 0)), np.nan)


def _torus(c, big, small, x, y):
    off = np.hypot(x - c[0], y - c[1]) - big
    inside = np.abs(off) < small
    return np.where(inside, c[2] + np.sqrt(np.maximum(small * small - off * off, 0)), np.nan)


C = (1.5, -2.0, 0.5)
SHAPES = [
    ("gr.sphere('s')", lambda x, y: _sphere((0, 0, 0), 1, x, y), 1.2),
    ("gr.cube('s')", lambda x, y: _box((0, 0, 0), 1, x, y), 1.2),
    ("gr.cylinder('s')", lambda x, y: _cylinder((0, 0, 0), 1, 2, x, y), 1.2),
    ("gr.cone('s')", lambda x, y: _cone((0, 0, 0), 1, 2, x, y), 2.2),
    ("gr.torus('s')", lambda x, y: _torus((0, 0, 0), 5, 2, x, y), 7.5),
    ("gr.nh_sphere('s', {1.5, -2, 0.5}, 0.8)", lambda x, y: _sphere(C, 0.8, x, y), 3.0),
    ("gr.nh_box('s', {1.5, -2, 0.5}, 0.8)", lambda x, y: _box(C, 0.8, x, y), 1.5),
    ("gr.nh_cylinder('s', {1.5, -2, 0.5}, 0.8, 2.5)", lambda x, y: _cylinder(C, 0.8, 2.5, x, y),
     3.5),
    ("gr.nh_cone('s', {1.5, -2, 0.5}, 0.8, 2.5)", lambda x, y: _cone(C, 0.8, 2.5, x, y), 3.5),
    ("gr.nh_torus('s', {1.5, -2, 0.5}, 0.9, 0.3)", lambda x, y: _torus(C, 0.9, 0.3, x, y), 3.0),
]  # fmt: skip


@pytest.mark.parametrize("command, reference, extent", SHAPES, ids=[s[0] for s in SHAPES])
def test_shapes_sit_where_the_report_puts_them(tmp_path, command, reference, extent):
    source = f"root = gr.node('root')\ns = {command}\nroot:add_child(s)\n" + render_call()
    (call,), _ = load(tmp_path, source)
    packed = pack_scene(call.scene, call.settings)
    grid = np.linspace(-extent, extent, 61) + 0.0123  # off the shapes' symmetry lines
    centre = (0.0, 0.0) if "nh_" not in command else C[:2]
    x, y = (a.ravel() + c for a, c in zip(np.meshgrid(grid, grid), centre, strict=True))
    origins = np.stack([x, y, np.full_like(x, 100.0)], axis=1)
    t, shape, _ = hits(packed, origins, np.tile([0.0, 0.0, -1.0], (len(x), 1)))
    expected = reference(x, y)
    # Rays within a hair of an outline may go either way; all others must agree exactly
    near = np.zeros(len(x), bool)
    for dx, dy in ((1e-6, 0), (-1e-6, 0), (0, 1e-6), (0, -1e-6)):
        near |= np.isnan(reference(x + dx, y + dy)) != np.isnan(expected)
    assert np.count_nonzero(~np.isnan(expected)) > 100
    assert np.array_equal((shape >= 0)[~near], ~np.isnan(expected)[~near])
    hit = ~np.isnan(expected) & ~near
    np.testing.assert_allclose(100.0 - t[hit], expected[hit], atol=1e-9)


@pytest.mark.parametrize(
    "command, top",
    [
        ("gr.nh_cylinder('s', {1, 2, 3}, 0.8, 2.5)", 2 + 1.25),
        ("gr.nh_cone('s', {1, 2, 3}, 0.8, 2.5)", 2 + 2.5),
        ("gr.cone('s')", 2.0),
        ("gr.cylinder('s')", 1.0),
    ],
)
def test_the_caps_face_up_the_y_axis(tmp_path, command, top):
    """Seen from above, the cylinder's top cap and the cone's base are flat discs."""
    source = f"root = gr.node('root')\ns = {command}\nroot:add_child(s)\n" + render_call()
    (call,), _ = load(tmp_path, source)
    centre = np.array(call.scene.shapes[0].world_from_object)[:3, 3]
    origins = centre * (1, 0, 1) + np.array([[0.1, 100, 0.2], [-0.3, 100, 0.1], [0.2, 100, -0.35]])
    t, shape, _ = hits(pack_scene(call.scene, call.settings), origins, [[0.0, -1.0, 0.0]] * 3)
    assert np.all(shape == 0)
    np.testing.assert_allclose(100.0 - t, top, atol=1e-9)


def _rotation(axis, degrees):
    """Rodrigues' formula, written independently of the loader's matrices."""
    k = np.eye(3)["xyz".index(axis)]
    a = math.radians(degrees)
    cross = np.array([[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]])
    m = np.eye(4)
    m[:3, :3] = np.eye(3) + math.sin(a) * cross + (1 - math.cos(a)) * cross @ cross
    return m


def test_transforms_apply_in_call_order_and_nest(tmp_path):
    source = (
        "root = gr.node('root')\nparent = gr.node('parent')\nroot:add_child(parent)\n"
        "parent:rotate('Y', 30)\nparent:translate(1, 2, 3)\n"
        "b = gr.nh_box('b', {0, 0, 0}, 2)\nb:scale(2, 1, 1)\nb:rotate('z', 45)\n"
        "b:translate(0, 1, 0)\nparent:add_child(b)\nroot:add_child(b)\n" + render_call()
    )
    (call,), _ = load(tmp_path, source)
    translate = np.eye(4)
    translate[:3, 3] = (1, 2, 3)
    parent = translate @ _rotation("y", 30)
    lift = np.eye(4)
    lift[:3, 3] = (0, 1, 0)
    box_node = lift @ _rotation("z", 45) @ np.diag([2.0, 1, 1, 1])
    cube = np.diag([1.0, 1, 1, 1])
    cube[:3, 3] = 1.0  # the core's [-1, 1]^3 onto the box from (0, 0, 0) of edge 2
    under_parent, under_root = (s.world_from_object for s in call.scene.shapes)
    np.testing.assert_allclose(under_parent, parent @ box_node @ cube, atol=1e-12)
    np.testing.assert_allclose(under_root, box_node @ cube, atol=1e-12)  # instanced twice


def test_a_point_light_on_a_plane_gives_the_closed_form_irradiance(tmp_path):
    """kd (I cos(theta) / (c0 + c1 d + c2 d^2) + ambient) straight below and off to the side."""
    kd, intensity, falloff, ambient = (0.5, 0.4, 0.3), 0.8, (1.0, 0.05, 0.002), 0.2
    source = (
        "root = gr.node('root')\n"
        "m = gr.material({0.5, 0.4, 0.3}, {0, 0, 0}, 1)\n"
        "floor = gr.nh_box('floor', {-50, -100, -50}, 100)\nfloor:set_material(m)\n"
        "root:add_child(floor)\n"
        "l = gr.light({3, 10, 0}, {0.8, 0.8, 0.8}, {1, 0.05, 0.002})\n"
        + render_call(lights="{l}", size=(9, 9), ambient="{0.2, 0.2, 0.2}",
                      camera=("{0, 20, 0}", "{0, -1, 0}", "{0, 0, -1}"))
    )  # fmt: skip
    (call,), _ = load(tmp_path, source)
    image = core.render(call.scene, call.settings).image
    d = math.hypot(3, 10)  # the centre pixel sees (0, 0, 0)
    irradiance = intensity * (10 / d) / (falloff[0] + falloff[1] * d + falloff[2] * d * d)
    expected = np.array(kd) * (irradiance + ambient)
    np.testing.assert_allclose(image[4, 4, :3], expected, rtol=1e-5)


def test_textures_keep_the_files_values_as_the_report_did(tmp_path):
    Image.new("RGB", (4, 4), (51, 102, 153)).save(tmp_path / "flat.png")
    source = (
        "root = gr.node('root')\nt = gr.texture('flat.png', {0, 0, 0}, 1, 0, 1, 1)\n"
        "s = gr.nh_sphere('s', {0, 0, 0}, 3)\ns:set_texture(t)\nroot:add_child(s)\n"
        + render_call(ambient="{1, 1, 1}")
    )
    (call,), _ = load(tmp_path, source)
    image = core.render(call.scene, call.settings).image
    np.testing.assert_allclose(image[4, 4, :3], np.array([51, 102, 153]) / 255, atol=1e-6)


REPORT_SUMMARY = """Calling A4_Render(
  SceneNode:[name:root, id:0]
  Image(width:500, height:500)
  eye:  vec3(0.000000, 0.000000, 800.000000)
  view: vec3(0.000000, 0.000000, -1.000000)
  up:   vec3(0.000000, 1.000000, 0.000000)
  fovy: 50
  ambient: vec3(0.300000, 0.300000, 0.300000)
  lights{
    L[vec3(0.900000, 0.900000, 0.900000), vec3(0.000000, 100.000000, 400.000000), 1, 0, 0; width: 50, height: 50]
  }
)

Max recursion level: 50
Supersampling is turned on
Soft shadow Ray number: 40
"""  # noqa: E501  (the report's line, as it printed it)


def test_the_report_manuals_examples_print_its_summaries():
    printed = []
    calls = load_script(SCENES / "report_manual.lua", print_line=printed.append)
    assert printed == [
        REPORT_SUMMARY + "Depth of field is turned off",
        REPORT_SUMMARY + "Depth of field is turned on\nFocal Length: 300\nAperture Radius: 20",
    ]
    plain, focused = calls
    assert plain.settings.pixel_samples == 3 and plain.settings.shadow_samples == 40
    assert focused.scene.camera.focal_distance == 300 and focused.scene.camera.aperture_radius == 20
    csg = next(s for s in plain.scene.shapes if isinstance(s, core.Csg))
    assert csg.operation == "intersection"
    assert isinstance(csg.left, core.Sphere) and isinstance(csg.right, core.Box)


def test_a_shape_without_material_renders_grey_with_a_warning(tmp_path):
    source = "root = gr.node('root')\nroot:add_child(gr.sphere('bare'))\n" + render_call()
    (call,), _ = load(tmp_path, source)
    assert call.warnings == ["1 shape(s) have no material ('bare'): they render grey"]


def test_a_csg_material_colours_operands_without_their_own(tmp_path):
    source = (
        "root = gr.node('root')\nm = gr.material({1, 0, 0}, {0, 0, 0}, 1)\n"
        "n = gr.material({0, 0, 1}, {0, 0, 0}, 1)\n"
        "a = gr.sphere('a')\nb = gr.cube('b')\nb:set_material(n)\n"
        "c = gr.csg(a, b, 'diff')\nc:set_material(m)\nroot:add_child(c)\n" + render_call()
    )
    (call,), _ = load(tmp_path, source)
    (csg,) = call.scene.shapes
    assert csg.operation == "difference"
    assert csg.left.material.diffuse == (1.0, 0.0, 0.0)
    assert csg.right.material.diffuse == (0.0, 0.0, 1.0)
    assert call.warnings == []


def test_the_final_scene_script_has_the_reports_settings():
    script = SCENES.parent.parent / "sample_blends" / "final_scene.lua"
    (call,) = load_script(script, print_line=lambda line: None)
    settings = call.settings
    assert (settings.width, settings.height, settings.max_depth) == (500, 500, 50)
    assert (settings.pixel_samples, settings.shadow_samples) == (3, 40)
    (light,) = call.scene.lights
    assert isinstance(light, core.AreaLight) and light.edge_u == (50.0, 0.0, 0.0)
    kinds = sorted(type(shape).__name__ for shape in call.scene.shapes)
    assert kinds == ["Box", "Cone", "Csg", "Csg", "Csg", "Mesh", "Mesh", "Sphere", "Torus",
                     "Torus"]  # fmt: skip
    assert call.output == script.with_name("final_scene_lua.png")
    assert call.warnings == []
