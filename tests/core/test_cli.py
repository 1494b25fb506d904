"""`python -m core render scene.lua`: the PNG, the exit status, and nothing partial left behind."""

import os
import shutil
import signal
import subprocess
import sys
import time

import numpy as np
import pytest
from PIL import Image

import core
from core.cli import main
from core.cs488 import load_script
from core.image_io import to_bytes
from tests.core.cs488.test_scenes import SCENES
from tests.support.exr import read_exr
from tests.support.terminal import ctrl_c_as_in_a_terminal

ROOT = SCENES.parent.parent


def run_cli(*args, cwd):
    return subprocess.run(
        [sys.executable, "-m", "core", *map(str, args)],
        cwd=cwd,
        capture_output=True,
        text=True,
        env={**os.environ, "PYTHONPATH": str(ROOT)},
        timeout=600,
    )


@pytest.fixture
def scenes(tmp_path):
    folder = tmp_path / "scenes"
    shutil.copytree(SCENES, folder, ignore=shutil.ignore_patterns("*.png", "*.blend"))
    shutil.copy(SCENES / "checker.png", folder)
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    return folder, elsewhere


def test_a_script_renders_to_its_png_from_any_folder(scenes):
    folder, elsewhere = scenes
    result = run_cli("render", folder / "every_command.lua", cwd=elsewhere)
    assert result.returncode == 0, result.stderr
    assert "Calling A4_Render(" in result.stdout and "Depth of field is turned on" in result.stdout
    assert "] 4/4 tiles" in result.stderr  # a 48 x 36 image is 2 x 2 tiles of 32
    written = folder / "every_command.png"
    assert f"wrote {written}" in result.stdout
    assert list(elsewhere.iterdir()) == []
    pixels = np.asarray(Image.open(written))
    # The same bytes as rendering in this process: a check of the command line's writing,
    # not of accuracy (cs488/test_scenes.py checks that against closed forms)
    (call,) = load_script(folder / "every_command.lua", print_line=lambda line: None)
    here = core.render(call.scene, call.settings).image
    expected = to_bytes(here)
    np.testing.assert_array_equal(pixels, expected)


def test_o_names_another_file_and_errors_leave_nothing(scenes):
    folder, elsewhere = scenes
    result = run_cli("render", folder / "every_command.lua", "-o", "out/picture.png", cwd=elsewhere)
    assert result.returncode == 0, result.stderr
    assert Image.open(elsewhere / "out" / "picture.png").size == (48, 36)
    assert not (folder / "every_command.png").exists()

    broken = folder / "broken.lua"
    source = (folder / "every_command.lua").read_text() + "\ngr.sphere('extra', 2)\n"
    broken.write_text(source)
    line = source.count("\n")
    result = run_cli("render", broken, cwd=elsewhere)
    assert result.returncode == 1
    assert result.stderr.strip() == (
        f"error: broken.lua:{line}: gr.sphere: takes 1 argument (name); got 2"
    )
    assert sorted(p.name for p in folder.glob("*.png")) == ["checker.png"]

    (folder / "empty.lua").write_text("x = 1\n")
    result = run_cli("render", folder / "empty.lua", cwd=elsewhere)
    assert result.returncode == 1 and "never calls gr.render" in result.stderr
    assert run_cli("paint", "x.lua", cwd=elsewhere).returncode == 2


def test_a_region_outside_the_image_names_the_option_before_rendering(scenes):
    folder, elsewhere = scenes
    script = folder / "every_command.lua"
    result = run_cli("render", script, "--region", "0,0,5000,5", cwd=elsewhere)
    assert result.returncode == 1
    assert result.stderr.strip() == (
        "error: --region: got (0, 0, 5000, 5); it must lie inside the 48x36 image "
        "(every_command.lua's gr.render size)"
    )
    result = run_cli("render", script, "--region", "3,2,0,5", cwd=elsewhere)
    assert result.returncode == 1 and "error: --region: got (3, 2, 0, 5)" in result.stderr
    assert sorted(p.name for p in folder.glob("*.png")) == ["checker.png"]


def test_ctrl_c_stops_the_render_and_writes_nothing(scenes):
    folder, elsewhere = scenes
    slow = folder / "slow.lua"
    slow.write_text(
        (folder / "every_command.lua")
        .read_text()
        .replace("'every_command.png', 48, 36", "'slow.png', 640, 480")
        .replace("4, 1, 4, 14, 0.02)", "8, 1, 64, 14, 0.02)")
    )
    process = subprocess.Popen(
        [sys.executable, "-m", "core", "render", str(slow)],
        cwd=elsewhere,
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        env={**os.environ, "PYTHONPATH": str(ROOT)},
        preexec_fn=ctrl_c_as_in_a_terminal,
    )
    assert process.stdout.readline().startswith("Calling A4_Render(")
    time.sleep(2.0)
    process.send_signal(signal.SIGINT)
    _, stderr = process.communicate(timeout=300)
    assert process.returncode == 130, stderr
    assert "interrupted: no image written" in stderr
    assert not (folder / "slow.png").exists()
    assert not list(folder.glob(".whitted-*"))


def test_o_with_several_render_calls_is_refused_before_rendering(capsys):
    """The report manual's script renders twice; one -o cannot name both images."""
    status = main(["render", str(SCENES / "report_manual.lua"), "-o", "one.png"])
    assert status == 1
    error = capsys.readouterr().err
    assert error.strip() == (
        "error: report_manual.lua: the script calls gr.render 2 times; -o names one file"
    )


def test_o_must_name_a_png_and_nothing_is_rendered_otherwise(capsys, tmp_path):
    status = main(["render", str(SCENES / "every_command.lua"), "-o", str(tmp_path / "out.jpg")])
    assert status == 1
    error = capsys.readouterr().err.strip()
    assert error.endswith("out.jpg: Whitted writes PNG images; name a file ending in .png"), error
    assert not list(tmp_path.iterdir())


def test_the_png_is_readable_by_others_as_any_new_file_is(scenes):
    """0644 under the usual umask 022, as Blender writes its images (not mkstemp's 0600)."""
    folder, elsewhere = scenes
    previous = os.umask(0o022)
    try:
        run = run_cli("render", folder / "every_command.lua", "-o", elsewhere / "x.png", cwd=folder)
    finally:
        os.umask(previous)
    assert run.returncode == 0, run.stderr
    assert (elsewhere / "x.png").stat().st_mode & 0o777 == 0o644


def test_passes_are_written_as_exr_files_beside_the_png(scenes):
    folder, elsewhere = scenes
    out = elsewhere / "picture.png"
    result = run_cli("render", folder / "every_command.lua", "-o", out,
                     "--passes", "depth,normal,crypto_object", cwd=elsewhere)  # fmt: skip
    assert result.returncode == 0, result.stderr
    assert sorted(p.name for p in elsewhere.iterdir()) == [
        "picture.crypto_object.exr", "picture.depth.exr", "picture.normal.exr", "picture.png",
    ]  # fmt: skip
    # The file's values are the render's (a check of the writing: test_passes checks the
    # values themselves against closed forms); read by an EXR reader of the tests' own
    (call,) = load_script(folder / "every_command.lua", print_line=lambda line: None)
    call.settings.passes = ("depth", "normal", "crypto_object")
    here = core.render(call.scene, call.settings).passes
    depth, _ = read_exr(elsewhere / "picture.depth.exr")
    np.testing.assert_array_equal(depth["Y"], here["depth"][..., 0])
    normal, _ = read_exr(elsewhere / "picture.normal.exr")
    np.testing.assert_array_equal(np.stack([normal[c] for c in "RGB"], -1), here["normal"])
    crypto, metadata = read_exr(elsewhere / "picture.crypto_object.exr")
    assert sorted(crypto)[:2] == ["CryptoObject00.A", "CryptoObject00.B"]
    (manifest,) = [v for k, v in metadata.items() if k.endswith("/manifest")]
    assert all(f'"{shape.name}"' in manifest for shape in call.scene.shapes)


def test_an_unknown_pass_is_refused_before_anything_runs(scenes):
    folder, elsewhere = scenes
    result = run_cli("render", folder / "every_command.lua", "--passes", "depth,zdepth",
                     cwd=elsewhere)  # fmt: skip
    assert result.returncode == 2
    assert "--passes: unknown pass 'zdepth'; use any of depth, mist" in result.stderr
    assert not (folder / "every_command.png").exists() and list(elsewhere.iterdir()) == []
