"""File > Import > CS488 Lua Scene with the hostile files and scripts of the command line's
corpora (tests/core/cs488/test_hostile_files.py, test_hostile_images.py): the operator's error
names the script's line and the reason, as the command line does, imports nothing, and is
never Whitted's own failure; a script that runs long says at once how to stop it."""

import pytest

from tests.blender.conftest import clear_scene
from tests.support.hostile import NORMAL
from tests.support.hostile_inputs import FILE_CASES, IMAGE_CASES

pytestmark = pytest.mark.bpy


def refused(bpy, script, says, **options):
    before = len(bpy.data.objects)
    with pytest.raises(RuntimeError) as error:
        bpy.ops.import_scene.cs488_lua(filepath=str(script), **options)
    message = str(error.value)
    assert "the import failed" not in message and "Whitted's fault" not in message, message
    assert says in message, message
    assert len(bpy.data.objects) == before
    return message


@pytest.mark.parametrize("case, line, make, message", FILE_CASES, ids=[c[0] for c in FILE_CASES])
def test_a_hostile_file_or_text_is_named_at_its_line(bpy_with_whitted, tmp_path, case, line,
                                                     make, message):  # fmt: skip
    bpy = bpy_with_whitted
    clear_scene(bpy)
    (tmp_path / "scene.lua").write_text(line + "\n" + NORMAL)
    if make is not None:
        make(tmp_path, line.split("'")[1] if "gr.mesh" not in line else line.split("'")[3])
    said = refused(bpy, tmp_path / "scene.lua", message)
    assert "scene.lua:" in said


@pytest.mark.parametrize("case, name, data, says", IMAGE_CASES, ids=[c[0] for c in IMAGE_CASES])
def test_a_hostile_texture_is_named_at_its_line(bpy_with_whitted, tmp_path, case, name, data,
                                                says):  # fmt: skip
    bpy = bpy_with_whitted
    clear_scene(bpy)
    (tmp_path / name).write_bytes(data)
    (tmp_path / "scene.lua").write_text(f"t = gr.texture('{name}', {{0, 0, 0}}, 1)\n" + NORMAL)
    said = refused(bpy, tmp_path / "scene.lua", f"scene.lua:1: gr.texture: texture file '{name}' ")
    assert says in said, said


def test_a_script_with_a_byte_order_mark_imports(bpy_with_whitted, tmp_path):
    bpy = bpy_with_whitted
    clear_scene(bpy)
    (tmp_path / "scene.lua").write_bytes(b"\xef\xbb\xbf" + NORMAL.encode())
    assert bpy.ops.import_scene.cs488_lua(filepath=str(tmp_path / "scene.lua")) == {"FINISHED"}


def test_a_long_script_says_how_to_stop_it_and_where_its_limit_is(bpy_with_whitted, tmp_path,
                                                                   capfd):  # fmt: skip
    bpy = bpy_with_whitted
    (tmp_path / "scene.lua").write_text("local n = 0\nwhile true do n = n + 1 end\n")
    # The import's Time Limit set to 4 s, as a user would in the file browser
    refused(bpy, tmp_path / "scene.lua", "past its time limit of 4 s", time_limit=4.0)
    output = capfd.readouterr().out
    assert (
        "Whitted: scene.lua is still running after 3 s: Ctrl-C stops it; it is stopped at 4 s "
        "(the import's Time Limit raises or lowers that)"
    ) in output, output
    assert bpy.context.scene is not None  # Blender stays usable
