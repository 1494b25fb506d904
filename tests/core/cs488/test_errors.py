"""Bad CS488 scripts: every mistake is reported with the file, the line and what is valid.

The report's program checked no arguments and failed silently; each case here is a mistake
it would have rendered wrongly or crashed on.
"""

import re

import pytest
from PIL import Image

from core.cs488 import ScriptError, load_script

RENDER = "gr.render(r, 'o.png', 8, 8, {0, 0, 5}, {0, 0, -1}, {0, 1, 0}, 50, {0, 0, 0}, {}"
M = "gr.material({1, 1, 1}, {0, 0, 0}, 1"

CASES = [
    # Argument counts
    ("gr.sphere()", "gr.sphere: takes 1 argument (name); got 0"),
    ("gr.nh_torus('t', {0, 0, 0}, 1)",
     "gr.nh_torus: takes 4 arguments (name, {x, y, z}, major_radius, minor_radius); got 3"),
    (M + ", 0, 1, 1.5, 7)", "gr.material: takes 3 to 6 arguments ({dr, dg, db}, {sr, sg, sb}, "
     "p[, reflectivity[, outer_ior[, inner_ior]]]); got 7"),
    ("gr.material({1, 1, 1}, {0, 0, 0})", "gr.material: takes 3 to 6 arguments"),
    ("gr.light({0, 0, 0}, {1, 1, 1}, {1, 0, 0}, 2)", "gr.light: takes 3 or 5 arguments"),
    ("r = gr.node('r') " + RENDER + ", 1, 2)", "gr.render: takes 10, 11, 13, 14, 15 or 16 "
     "arguments"),
    # Whitted's options table (core.cs488.render_options)
    ("r = gr.node('r') " + RENDER + ", 1)",
     "gr.render: the options after the lights must be a table {caustics = "),
    ("r = gr.node('r') " + RENDER + ", {caustic = 'both'})",
     "gr.render: options {caustic}: not an option of gr.render; it takes {caustics = "),
    ("r = gr.node('r') " + RENDER + ", {caustics = 'mirrors'})",
     "gr.render: options.caustics must be one of 'none', 'reflective', 'refractive', 'both', "
     "true or false; got 'mirrors'"),
    ("r = gr.node('r') " + RENDER + ", {photons = 2.5})",
     "gr.render: options.photons must be a whole number from 0 to 10,000,000 or 'auto'; got 2.5"),
    ("r = gr.node('r') " + RENDER + ", {photons = 1/0})",
     "gr.render: options.photons must be a whole number from 0 to 10,000,000 or 'auto'; got inf"),
    ("r = gr.node('r') " + RENDER + ", {glass_shadows = 'none'})",
     "gr.render: options.glass_shadows must be 'attenuated' or 'blocked'; got 'none'"),
    ("r = gr.node('r') " + RENDER + ", 4, 1, {})",
     "gr.render: the options table comes last, after 10, 13 or 15 arguments; got it after 12"),
    ("r = gr.node('r') r:translate(1, 2)", "node:translate: takes 3 arguments (x, y, z); got 2"),
    ("r = gr.node('r') r:rotate('x')", "node:rotate: takes 2 arguments (axis, degrees); got 1"),
    # Argument types and ranges
    ("gr.sphere(3)", "gr.sphere: name must be a string; got the number 3"),
    ("gr.nh_sphere('s', {0, 0}, 1)",
     "gr.nh_sphere: centre {x, y, z} must be a table of 3 numbers; got a table of 2 values"),
    ("gr.nh_sphere('s', {0, 0, 'x'}, 1)",
     "gr.nh_sphere: centre {x, y, z} value 3 must be a number; got the string 'x'"),
    ("gr.nh_box('b', {0, 0, 0}, 'big')", "gr.nh_box: size must be a number; got the string 'big'"),
    ("gr.nh_cone('c', {0, 0, 0}, 1, 0)", "gr.nh_cone: height must be above 0; got 0"),
    (M + ", 2)", "gr.material: reflectivity must be between 0 and 1; got 2"),
    (M + ", 0, 0, 1.5)", "gr.material: indices of refraction 0 (outer) and 1.5 (inner): equal "
     "indices (`0, 0` in the report's scripts) mean no refraction; to refract, both must be "
     "above 0"),
    (M + ", 0, -1, -1)", "gr.material: outer index of refraction must be"),
    ("gr.light({0, 0, 0}, {1, 1, 1}, {0, 0, 0})",
     "gr.light: falloff {c0, c1, c2} cannot be all 0; (1, 0, 0) is no falloff"),
    ("r = gr.node('r') r:rotate('w', 30)",
     "node:rotate: node 'r': axis must be 'x', 'y' or 'z'; got the string 'w'"),
    ("r = gr.node('r') r:scale(1, 0, 1)", "node:scale: node 'r': scale by (1.0, 0.0, 1.0): a "
     "factor of 0 flattens the node"),
    ("r = gr.node('r') r:set_material(" + M + "))",
     "node:set_material: node 'r' has no shape to colour; set materials on shape nodes"),
    ("s = gr.sphere('s') s:set_texture(" + M + "))",
     "node:set_texture: sphere 's': material 1 goes on with set_material, not set_texture"),
    ("s = gr.sphere('s') s:set_material(gr.texture('t.png', {0, 0, 0}, 1))",
     "node:set_material: sphere 's': texture 1 goes on with set_texture, not set_material"),
    ("r = gr.node('r') " + RENDER.replace("o.png", "o.jpg") + ")",
     "gr.render: file 'o.jpg' must name a .png image"),
    ("r = gr.node('r') " + RENDER.replace("8, 8", "8.5, 8") + ")",
     "gr.render: width must be a whole number of at least 1; got 8.5"),
    ("r = gr.node('r') " + RENDER.replace("50,", "180,") + ")",
     "gr.render: fovy: got 180.0; use an angle between 0 and 180"),
    ("r = gr.node('r') " + RENDER.replace("{}", "{gr.node('x')}") + ")",
     "gr.render: lights[1] is node 'x'; lights come from gr.light"),
    ("r = gr.node('r') " + RENDER + ", 5, 1, 0)",
     "gr.render: soft shadow ray number must be a whole number of at least 1; got 0"),
    # CSG
    ("a = gr.sphere('a') b = gr.cube('b') gr.csg(a, b, 'xor')",
     "gr.csg: unknown operation 'xor'; use 'union', 'intersection' or 'diff'"),
    ("a = gr.sphere('a') gr.csg(a, gr.node('n'), 'union')",
     "gr.csg: the second operand must be a shape or CSG node; got node 'n'"),
    ("r = gr.node('r') a = gr.sphere('a') r:add_child(a) gr.csg(a, gr.cube('b'), 'union')",
     "gr.csg: the first operand, sphere 'a', has a parent or children"),
    ("a = gr.sphere('a') c = gr.csg(a, gr.cube('b'), 'union') gr.node('r'):add_child(a)",
     "node:add_child: sphere 'a' is an operand of CSG node 'a union b'; add the CSG node"),
    # Files
    ("gr.mesh('m', 'nope.obj')", "gr.mesh: mesh file 'nope.obj' not found (looked for "),
    ("gr.mesh('m', 'bad.obj')",
     "gr.mesh: mesh file 'bad.obj': no vertices ('v' lines): not an OBJ mesh"),
    ("gr.texture('nope.png', {0, 0, 0}, 1)", "gr.texture: texture file 'nope.png' not found"),
    ("gr.texture('bad.obj', {0, 0, 0}, 1)", "gr.texture: texture file 'bad.obj' is not an image"),
    # The node graph
    ("r = gr.node('r') a = gr.sphere('a') r:add_child(a) r:add_child(a)",
     "node:add_child: sphere 'a' is already a child of node 'r'; a node is added once"),
    ("r = gr.node('r') a = gr.node('a') r:add_child(a) a:add_child(r)",
     "node:add_child: adding node 'r' under node 'a' makes a cycle (node 'r' -> node 'a' -> "
     "node 'r')"),
    ("r = gr.node('r') r:add_child({})",
     "node:add_child: node 'r': the child must be a node; got a table of 0 values"),
]  # fmt: skip


@pytest.fixture
def folder(tmp_path):
    (tmp_path / "bad.obj").write_text("hello world\n")
    Image.new("RGB", (2, 2)).save(tmp_path / "t.png")
    return tmp_path


@pytest.mark.parametrize("source, message", CASES, ids=[c[1][:60] for c in CASES])
def test_each_mistake_names_the_file_line_and_what_is_valid(folder, source, message):
    script = folder / "scene.lua"
    script.write_text("root = gr.node('root')\n\n" + source + "\n")
    with pytest.raises(ScriptError) as caught:
        load_script(script, print_line=lambda line: None)
    assert re.match(r"scene\.lua:3: " + re.escape(message), str(caught.value)), caught.value


@pytest.mark.parametrize(
    "source, message",
    [
        ("error('plain')", "scene.lua:3: plain"),
        ("error(42)", "scene.lua:3: 42"),
        ("error()", "scene.lua:3: error() was called with no message (a table or nil, not text)"),
        # A table carries no message and Lua gives no traceback with it: the file alone
        ("error({code = 1})", "scene.lua: error() was called with no message"),
    ],
)
def test_the_scripts_own_error_names_the_place_whatever_it_raises(folder, source, message):
    script = folder / "scene.lua"
    script.write_text("root = gr.node('root')\n\n" + source + "\n")
    with pytest.raises(ScriptError) as caught:
        load_script(script, print_line=lambda line: None)
    assert str(caught.value).startswith(message), caught.value
    assert "stack traceback" not in str(caught.value)


def test_an_error_after_gr_render_still_renders_nothing(folder):
    script = folder / "scene.lua"
    script.write_text("r = gr.node('r')\n" + RENDER + ")\ngr.sphere()\n")
    with pytest.raises(ScriptError, match=r"^scene\.lua:3: gr\.sphere: takes 1 argument"):
        load_script(script, print_line=lambda line: None)


@pytest.mark.parametrize(
    "source",
    ["os.execute('touch pwned')", "io.open('../outside.txt')", "dofile('../outside.lua')",
     "loadfile('../outside.lua')", "require('outside')", "io.lines('../outside.txt')"],
)  # fmt: skip
def test_scripts_cannot_reach_files_outside_their_folder(tmp_path, source):
    (tmp_path / "outside.lua").write_text("gr.sphere('leaked')\n")
    (tmp_path / "outside.txt").write_text("secret\n")
    folder = tmp_path / "scene"
    folder.mkdir()
    (folder / "scene.lua").write_text(source + "\n")
    with pytest.raises(ScriptError, match=r"^scene\.lua:1: attempt to (index|call) a nil value"):
        load_script(folder / "scene.lua", print_line=lambda line: None)
    assert not (folder / "pwned").exists()


def test_equal_indices_as_the_seeds_scripts_write_them_mean_no_refraction(folder):
    """`gr.material(kd, ks, p, r, 0, 0)` is how the report's scripts say "not glass": the
    same material as one given no indices at all."""
    script = folder / "scene.lua"
    lines = ["r = gr.node('r')"]
    for name, tail in (("seed", ", 0.3, 0, 0"), ("equal", ", 0.3, 1.5, 1.5"), ("plain", ", 0.3")):
        lines += [f"{name} = gr.sphere('{name}')", f"r:add_child({name})"]
        lines += [f"{name}:set_material(gr.material({{1, 0, 0}}, {{0, 0, 0}}, 1{tail}))"]
    script.write_text("\n".join(lines) + "\n" + RENDER + ")\n")
    (call,) = load_script(script, print_line=lambda line: None)
    materials = {shape.name: shape.material for shape in call.scene.shapes}
    for name in ("seed", "equal"):
        assert materials[name].transparency == 0.0
        assert (materials[name].outer_ior, materials[name].inner_ior) == (1.0, 1.0)
        assert materials[name].reflectivity == materials["plain"].reflectivity == 0.3
