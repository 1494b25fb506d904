"""What a final render tells a Blender user, read back from Blender: the summary in a
user's words; the first-use kernel compile shown in the render's own progress bar and header
and kept out of the render time (said apart in the metadata); a render cancelled during the
compile says so; warnings outlast the summary in the status bar and stay in the metadata.

The warm-up here is a stand-in child (a shell script printing the real one's progress lines
with pauses), so that no test compiles; the real cold compile's metadata is checked in
test_blender34_cli."""

import re
import stat
import sys
import time

import numpy as np
import pytest
from PIL import Image

from core.jit.warmup import STEP_SHARES

pytestmark = pytest.mark.bpy


def final_render():
    return sys.modules["whitted.engine.final"]


class Recorder:
    """Stands for the RenderEngine Blender made, recording what the render tells the user
    (progress, header text, reports) and passing everything on to it."""

    def __init__(self, engine, seen):
        self._engine, self._seen = engine, seen

    def __getattr__(self, name):
        return getattr(self._engine, name)

    def update_progress(self, value):
        self._seen.append(("progress", value))
        self._engine.update_progress(value)

    def update_stats(self, stats, info):
        self._seen.append(("stats", info))
        self._engine.update_stats(stats, info)

    def report(self, kind, message):
        self._seen.append((next(iter(kind)), message))
        self._engine.report(kind, message)


@pytest.fixture
def seen(monkeypatch):
    """What the next render tells the user, in order."""
    told = []
    real = final_render().render
    monkeypatch.setattr(
        final_render(), "render", lambda engine, depsgraph: real(Recorder(engine, told), depsgraph)
    )
    return told


def stand_in_warmup(tmp_path, monkeypatch, body):
    """A WarmupProcess running `body` as its child, in place of the shared warm-up, as on a
    machine whose kernel cache is empty."""
    core = sys.modules["whitted.core"]
    monkeypatch.setattr(core.jit.warmup_process, "kernels_ready", lambda *unused: False)
    script = tmp_path / "warmup.sh"
    script.write_text("#!/bin/sh\n" + body)
    script.chmod(script.stat().st_mode | stat.S_IXUSR)
    return core.jit.warmup_process.WarmupProcess([str(script)])


def rendered_metadata(bpy, scene, path):
    scene.render.filepath = str(path)
    bpy.ops.render.render(write_still=True)
    return Image.open(path).info


def test_the_summary_speaks_a_users_words_and_fits_a_line(sample_scene, bpy_with_whitted, tmp_path):
    kept = rendered_metadata(bpy_with_whitted, sample_scene, tmp_path / "summary.png")
    summary = kept["Whitted"]
    assert re.fullmatch(
        r"\d+\.\d\d s \| 160x120 \| [\d.]+ M rays, \d+ threads"
        r"( \| \+\d\.\d\d s loading kernels| \| \+\d+ s first-use compile)?",
        summary,
    ), summary  # a first-use compile when this test ran first, on a cold cache
    assert "memory" not in summary and len(summary) <= 100, summary
    assert re.fullmatch(r"\d+\.\d\d s", kept["Whitted Render Time"]), kept
    kernels = ("kernels already loaded", "kernels loaded", "first-use kernel compile")
    assert kept["Whitted Kernels"].startswith(kernels), kept


def test_the_log_gives_farms_the_figures_the_summary_shortens(
    sample_scene, bpy_with_whitted, tmp_path, capfd
):
    # The farm adds its tasks' rays and render times up from this line (a summary it cannot
    # read gives a farm report of 0 rays: what the fresh-clone run caught)
    from core.farm.worker import SUMMARY

    capfd.readouterr()
    rendered_metadata(bpy_with_whitted, sample_scene, tmp_path / "log.png")
    out = capfd.readouterr().out
    (figures,) = [m.groupdict() for m in SUMMARY.finditer(out)]
    assert float(figures["seconds"]) > 0 and float(figures["rays"]) > 0, out[-2000:]
    assert re.search(r"^Whitted \| 160x120 \| export [\d.]+ s \| kernels \w+ [\d.]+ s \| ", out,
                     re.MULTILINE), out[-2000:]  # fmt: skip


def test_the_first_use_compile_drives_the_progress_bar_and_is_kept_out_of_the_render_time(
    sample_scene, bpy_with_whitted, tmp_path, monkeypatch, seen
):
    steps = ["1 of 5 (scene packing)", "2 of 5 (nearest hits)", "3 of 5 (shadow rays)",
             "4 of 5 (render kernel)", "5 of 5 (caustic photons)"]  # fmt: skip
    body = "".join(f'echo "Whitted: compiling kernels: {step}"\nsleep 0.7\n' for step in steps)
    warmup = stand_in_warmup(tmp_path, monkeypatch, body)
    monkeypatch.setattr(final_render(), "shared_warmup", lambda **unused: warmup)
    kept = rendered_metadata(bpy_with_whitted, sample_scene, tmp_path / "first.png")
    # Before the first tile: the bar follows the compile, step by step, never backwards
    first_tile = next(i for i, (kind, text) in enumerate(seen) if "Tile" in str(text)) - 1
    progress = [value for kind, value in seen[:first_tile] if kind == "progress"]
    assert len(progress) >= 3 and progress == sorted(progress), progress
    # It starts near 0 and reaches the last step's start (the shares of the steps before it)
    before_last = sum(list(STEP_SHARES.values())[:4])
    assert progress[0] < 0.2 and progress[-1] >= before_last - 1e-6, progress
    headers = [text for kind, text in seen[:first_tile] if kind == "stats"]
    shown = re.compile(
        r"Whitted \| Compiling kernels \(first use on this machine, not render time\): \d+ %, \d+ s"
    )
    assert any(shown.fullmatch(text) for text in headers), headers
    # Said apart: the compile's seconds in their own field, the render time without them
    compiled = re.match(r"first-use kernel compile (\d+) s", kept["Whitted Kernels"])
    assert compiled and int(compiled.group(1)) >= 2, kept
    assert float(kept["Whitted Render Time"].removesuffix(" s")) < 1.5, kept
    assert re.search(r" \| \+\d+ s first-use compile$", kept["Whitted"]), kept


def test_a_slow_cache_check_is_no_compile(sample_scene, bpy_with_whitted, tmp_path, monkeypatch):
    # On a busy machine the warm-up's check of a full cache (and its copy of an extension's
    # shipped kernels) took 0.2 s; the summary called it a "+0 s first-use compile" (the
    # fresh-clone run's extension test)
    core = sys.modules["whitted.core"]
    monkeypatch.setattr(core.jit.warmup_process, "kernels_ready", lambda *unused: True)
    warmup = core.jit.warmup_process.WarmupProcess(["false"])
    real_start = warmup.start
    monkeypatch.setattr(warmup, "start", lambda: (time.sleep(0.3), real_start()))
    monkeypatch.setattr(final_render(), "shared_warmup", lambda **unused: warmup)
    kept = rendered_metadata(bpy_with_whitted, sample_scene, tmp_path / "slow_check.png")
    assert "compile" not in kept["Whitted"] + kept["Whitted Kernels"], kept


def test_esc_during_the_compile_says_the_render_was_cancelled(
    sample_scene, bpy_with_whitted, tmp_path, monkeypatch, seen
):
    warmup = stand_in_warmup(
        tmp_path,
        monkeypatch,
        'echo "Whitted: compiling kernels: 1 of 5 (scene packing)"\nsleep 30\n',
    )
    monkeypatch.setattr(final_render(), "shared_warmup", lambda **unused: warmup)
    pressed = time.monotonic() + 0.5
    monkeypatch.setattr(final_render(), "cancelled", lambda engine: time.monotonic() > pressed)
    try:
        bpy_with_whitted.ops.render.render()
    finally:
        warmup._process.kill()  # the stand-in would go on for 30 s, as a real one goes on
    said = [text for kind, text in seen if kind in ("INFO", "stats")]
    assert any("render cancelled while the kernels compiled" in text for text in said), said
    assert not any("Tile" in str(text) for _, text in seen)


def test_warnings_outlast_the_summary_and_stay_with_the_picture(
    sample_scene, bpy_with_whitted, tmp_path, seen
):
    light = next(o for o in sample_scene.objects if o.type == "LIGHT")
    light.data.shadow_soft_size = 0.5  # unused by its CS488 light model
    kept = rendered_metadata(bpy_with_whitted, sample_scene, tmp_path / "warned.png")
    reports = [(kind, text) for kind, text in seen if kind in ("INFO", "WARNING", "ERROR")]
    # The last report (what the status bar shows when the render ends) is the warning
    kind, text = reports[-1]
    assert kind == "WARNING" and f"light '{light.name}'" in text, reports
    assert any(kind == "INFO" and text.startswith("Whitted | ") for kind, text in reports)
    assert "Radius 0.5 m" in kept["Whitted Warnings"], kept
    image = np.asarray(Image.open(tmp_path / "warned.png"))
    assert image.shape[:2] == (120, 160)


def test_a_scene_whose_features_cannot_be_foreseen_renders_with_the_full_kernel(
    sample_scene, bpy_with_whitted, tmp_path, monkeypatch, seen
):
    """The features a scene may use are only a hint for the warm-up (core.compile.features):
    where reading them fails, the warm-up is the full kernel's and the render goes on (a
    scene the compile refuses gets its own clear error there)."""
    features = sys.modules["whitted.core.compile.features"]

    def fails(scene, settings):
        raise ValueError("a graph the hint cannot read")

    monkeypatch.setattr(features, "expected_features", fails)
    monkeypatch.setenv("WHITTED_FULL_KERNEL", "0")
    assert final_render().kernel_features_unused(None, None) == frozenset()
    kept = rendered_metadata(bpy_with_whitted, sample_scene, tmp_path / "unforeseen.png")
    assert "Whitted" in kept and not any(kind == "ERROR" for kind, _ in seen), seen
