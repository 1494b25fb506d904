"""Hostile texture files, each named by a script run as a user runs it (`python -m core
render`): the script's line names the file and why it cannot be read (decoder limits
included), exit 1, no traceback, nothing written. Before, a PNG whose text chunk was too
large to decompress killed the process running the script ("this is Whitted's fault")."""

import time

import numpy as np
import pytest
from PIL import Image

from tests.support.hostile import NORMAL, assert_refused, run
from tests.support.hostile_inputs import IMAGE_CASES


@pytest.mark.parametrize("case, name, data, says", IMAGE_CASES, ids=[c[0] for c in IMAGE_CASES])
def test_a_hostile_texture_is_named_at_the_scripts_line(tmp_path, case, name, data, says):
    (tmp_path / name).write_bytes(data)
    (tmp_path / "scene.lua").write_text(f"t = gr.texture('{name}', {{0, 0, 0}}, 1)\n" + NORMAL)
    before = sorted(p.name for p in tmp_path.iterdir())
    start = time.monotonic()
    result = run(tmp_path, tmp_path / "scene.lua")
    assert time.monotonic() - start < 60
    assert_refused(result, f"error: scene.lua:1: gr.texture: texture file '{name}' ", says)
    assert sorted(p.name for p in tmp_path.iterdir()) == before


def test_a_16_bit_grey_texture_renders_as_its_8_bit_twin(tmp_path):
    """End to end: a 16-bit grey PNG of 0.25 renders as an 8-bit PNG of 64/255 does (it
    rendered all white)."""
    Image.fromarray(np.full((8, 8), round(0.25 * 65535), np.uint16)).save(tmp_path / "a.png")
    Image.fromarray(np.full((8, 8), 64, np.uint8)).save(tmp_path / "b.png")
    pictures = []
    for texture in ("a.png", "b.png"):
        scene = f"t = gr.texture('{texture}', {{0, 0, 0}}, 1)\n" + NORMAL.replace(
            "r:add_child(gr.sphere('s'))", "s = gr.sphere('s')\ns:set_texture(t)\nr:add_child(s)"
        ).replace("{0, 0, 0}, {})", "{1, 1, 1}, {})")
        (tmp_path / "scene.lua").write_text(scene)
        assert run(tmp_path, tmp_path / "scene.lua").returncode == 0
        pictures.append(np.asarray(Image.open(tmp_path / "o.png"), np.int16))
    assert pictures[1][4, 4, 0] > 40  # the sphere is lit by the ambient term: not black
    assert np.max(np.abs(pictures[0] - pictures[1])) <= 1


def test_the_message_names_a_file_by_the_scripts_name_of_it(tmp_path):
    (tmp_path / "sub").mkdir()
    (tmp_path / "sub" / "t.png").write_bytes(b"")
    (tmp_path / "scene.lua").write_text("t = gr.texture('sub/t.png', {0, 0, 0}, 1)\n")
    result = run(tmp_path, "scene.lua")
    assert "texture file 'sub/t.png' is not an image" in result.stderr
