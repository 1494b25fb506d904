"""Whitted's extension of gr.render (core.cs488.render_options): an options table after the
report's arguments, and the command line's --caustics, --photons and --glass-shadows. A
script without them keeps the report's settings; with them, the photons run and the
report's own lights light the floor through a mirror (the light's closed form is checked in
tests/core/test_caustics.py; here, that the switches reach the render)."""

import pytest

from core import render
from core.cli import main
from tests.core.cs488.test_scenes import load

# A mirror wall at x = 0 facing +x, a point light before it, a floor seen from above
MIRROR_SCENE = """
floor = gr.material({1, 1, 1}, {0, 0, 0}, 1)
mirror = gr.material({0, 0, 0}, {0, 0, 0}, 1, 0.9)
root = gr.node('root')
f = gr.cube('floor')
f:scale(20, 1, 20)
f:translate(-10, -1, -10)
f:set_material(floor)
root:add_child(f)
m = gr.cube('mirror')
m:scale(0.1, 2, 2)
m:translate(-0.1, 0, -1)
m:set_material(mirror)
root:add_child(m)
lamp = gr.light({1, 1.5, 0}, {1, 1, 1}, {1, 0, 0})
"""
CAMERA = "{1.5, 10, 0}, {0, -1, 0}, {0, 0, -1}, 20, {0, 0, 0}, {lamp}"


def _render_line(extra=""):
    return f"gr.render(root, 'out.png', 24, 24, {CAMERA}{extra})\n"


def test_without_options_a_script_keeps_the_reports_settings(tmp_path):
    (call,), printed = load(tmp_path, MIRROR_SCENE + _render_line())
    settings = call.settings
    assert (settings.caustics, settings.glass_shadows) == ((), "attenuated")
    assert not any("Caustics" in line for line in printed)


@pytest.mark.parametrize(
    "table, caustics, rule, photons",
    [
        ("{caustics = 'both'}", ("reflective", "refractive"), "blocked", "auto"),
        ("{caustics = true, photons = 5000}", ("reflective", "refractive"), "blocked", 5000),
        ("{caustics = 'reflective'}", ("reflective",), "attenuated", "auto"),
        ("{caustics = 'refractive', glass_shadows = 'attenuated'}", ("refractive",),
         "attenuated", "auto"),
        ("{glass_shadows = 'blocked'}", (), "blocked", "auto"),
        ("{}", (), "attenuated", "auto"),
    ],
)  # fmt: skip
def test_the_options_table_sets_caustics_photons_and_the_glass_rule(
    tmp_path, table, caustics, rule, photons
):
    (call,), printed = load(tmp_path, MIRROR_SCENE + _render_line(", " + table))
    settings = call.settings
    assert (settings.caustics, settings.glass_shadows) == (caustics, rule)
    assert settings.caustic_photons == photons
    if table != "{}":
        assert f"Glass shadows: {rule}" in printed[-1]


def test_the_options_follow_the_reports_extra_arguments_too(tmp_path):
    (call,), _ = load(tmp_path, MIRROR_SCENE + _render_line(", 3, 0, 2, {caustics = 'both'}"))
    assert (call.settings.max_depth, call.settings.shadow_samples) == (3, 2)
    assert call.settings.caustics == ("reflective", "refractive")


def _floor_brightness(tmp_path, extra):
    (call,), _ = load(tmp_path, MIRROR_SCENE + _render_line(extra))
    image = render(call.scene, call.settings).image[..., :3].astype(float).mean(axis=-1)
    return image[:, 6:].mean()  # the floor beside the mirror's foot (image x is world x)


def test_a_script_asking_for_caustics_gets_the_mirrors_light_on_the_floor(tmp_path):
    plain = _floor_brightness(tmp_path, "")
    lit = _floor_brightness(tmp_path, ", {caustics = 'reflective', photons = 20000}")
    assert lit > 1.3 * plain, (lit, plain)


def test_the_command_line_options_override_the_script(tmp_path, capsys):
    script = tmp_path / "mirror.lua"
    script.write_text(MIRROR_SCENE + _render_line(", {caustics = 'none'}"))
    status = main(["render", str(script), "--caustics", "reflective", "--photons", "20000",
                   "--threads", "1"])  # fmt: skip
    captured = capsys.readouterr()
    out = captured.out
    assert status == 0
    assert "caustic photons" in captured.err  # the pass's progress bar, before the tiles'
    assert captured.err.index("caustic photons") < captured.err.index(" tiles ")
    assert "Caustics: reflective (20,000 photons)" not in out  # the script's line is its own
    assert "photons traced" in out, out  # the render's summary: the pass ran
    # and none when the command line turns them off over a script asking for them
    script.write_text(MIRROR_SCENE + _render_line(", {caustics = 'both'}"))
    assert main(["render", str(script), "--caustics", "none", "--threads", "1"]) == 0
    assert "photons traced" not in capsys.readouterr().out
    # --photons auto over a script's count: the automatic budget's
    script.write_text(MIRROR_SCENE + _render_line(", {caustics = 'both', photons = 5000}"))
    assert main(["render", str(script), "--photons", "auto", "--threads", "1"]) == 0
    assert "photons traced (automatic)" in capsys.readouterr().out


@pytest.mark.parametrize(
    "args, message",
    [
        (["--caustics", "mirrors"], "argument --caustics: invalid choice: 'mirrors'"),
        (["--photons", "-5"], "give a whole number of photons from 0 to 10,000,000, or auto"),
        (["--photons", "lots"], "got 'lots'; give a whole number of photons from 0 to 10,000,"),
        (["--glass-shadows", "grey"], "argument --glass-shadows: invalid choice: 'grey'"),
    ],
)
def test_bad_command_line_options_are_refused_before_anything_runs(tmp_path, capsys, args,
                                                                   message):  # fmt: skip
    script = tmp_path / "mirror.lua"
    script.write_text(MIRROR_SCENE + _render_line())
    with pytest.raises(SystemExit) as exit_:
        main(["render", str(script), *args])
    assert exit_.value.code == 2
    assert message in capsys.readouterr().err
    assert not (tmp_path / "out.png").exists()
