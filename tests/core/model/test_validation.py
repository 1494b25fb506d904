"""Bad input raises SceneError naming the object and the field, before any rendering."""

import numpy as np
import pytest

from core import Camera, Material, PointLight, RenderSettings, Scene, SceneError, Sphere, render
from tests.support.scenes import ball_on_ground


def render_tiny(scene, settings=None):
    return render(scene, settings or RenderSettings(4, 4))


def test_zero_scale_sphere_is_named():
    scene = ball_on_ground()
    scene.shapes[0].world_from_object = np.diag([1.0, 0.0, 1.0, 1.0])
    with pytest.raises(SceneError, match=r"sphere 'Ball': world_from_object: .*non-zero scale"):
        render_tiny(scene)


@pytest.mark.parametrize("field", ["width", "height"])
def test_zero_resolution(field):
    settings = RenderSettings(4, 4)
    setattr(settings, field, 0)
    with pytest.raises(SceneError, match=rf"render settings: {field}: got 0; use a whole number"):
        render_tiny(ball_on_ground(), settings)


@pytest.mark.parametrize(
    "field, value, allowed",
    [
        # 2**32 overflowed the kernels' sample numbers into black pixels
        ("pixel_samples", 2**32, "from 1 to 1024"),
        ("shadow_samples", 2**32, "from 1 to 65536"),
        ("seed", 2**64, "from 0 to 9223372036854775807"),
        # 1e12 bounces asked for 21.8 TiB of ray stack
        ("max_depth", 10**12, "from 0 to 10000"),
    ],
)
def test_sample_counts_and_seed_past_what_the_kernels_count_are_refused(field, value, allowed):
    settings = RenderSettings(4, 4)
    setattr(settings, field, value)
    with pytest.raises(SceneError, match=rf"render settings: {field}: got {value}; .*{allowed}"):
        render_tiny(ball_on_ground(), settings)


@pytest.mark.parametrize(
    "change, message",
    [
        (lambda s: setattr(s.camera, "fovy", 0.0), r"camera 'Camera': fovy: got 0.0"),
        (lambda s: setattr(s.camera, "fovy", 180.0), r"camera 'Camera': fovy"),
        (lambda s: setattr(s.camera, "up", (0.0, 14.0, -5.0)), r"camera 'Camera': up: .*parallel"),
        (lambda s: setattr(s.camera, "view", (0, 0, 0)), r"camera 'Camera': view: .*non-zero"),
        # So short that normalising it underflows (found by the fuzzer)
        (lambda s: setattr(s.camera, "up", (0, 0, 1e-200)), r"camera 'Camera': up: .*length"),
        (
            lambda s: setattr(s.camera, "eye", (0, float("nan"), 0)),
            r"camera 'Camera': eye: .*finite",
        ),
        (lambda s: setattr(s.lights[0], "attenuation", (0, 0, 0)), r"light 'Key': attenuation"),
        (
            lambda s: setattr(s.lights[0], "intensity", (1, -1, 1)),
            r"light 'Key': intensity: .*>= 0",
        ),
        (
            lambda s: setattr(s.shapes[0].material, "shininess", -2.0),
            r"material 'ball' \(on sphere 'Ball'\): shininess",
        ),
        (lambda s: setattr(s.shapes[1].material, "diffuse", (1, 2)), r"material 'ground'.*diffuse"),
        (lambda s: setattr(s.shapes[0], "material", "red"), r"sphere 'Ball': material: got str"),
        (lambda s: setattr(s, "ambient", (-1, 0, 0)), r"scene: ambient"),
        (
            lambda s: setattr(s.shapes[0], "casts_shadows", "no"),
            r"sphere 'Ball': casts_shadows: got 'no'; need True or False",
        ),
        (
            lambda s: setattr(s.shapes[0].material, "bump_rule", True),
            r"material 'ball' \(on sphere 'Ball'\): bump_rule: .*corrected, uncorrected, displaced",
        ),
    ],
)
def test_bad_fields_are_named(change, message):
    scene = ball_on_ground()
    change(scene)
    with pytest.raises(SceneError, match=message):
        render_tiny(scene)


def test_nan_in_transform_and_non_affine_rows():
    scene = Scene(Camera(), [Sphere("S", Material(), np.full((4, 4), np.nan))], [PointLight()])
    with pytest.raises(SceneError, match="sphere 'S': world_from_object: contains NaN"):
        render_tiny(scene)
    scene.shapes[0].world_from_object = np.ones((4, 4))
    with pytest.raises(SceneError, match="bottom row"):
        render_tiny(scene)


def test_the_bump_terminator_must_be_a_rule_by_name():
    """RenderSettings.bump_terminator was a flag before it named Cycles' rules: an old True
    is refused, naming the field and the rules."""
    with pytest.raises(SceneError, match=r"bump_terminator: .*chiang, conty"):
        render_tiny(ball_on_ground(), RenderSettings(4, 4, bump_terminator=True))


def test_shadow_culling_must_be_a_flag():
    settings = RenderSettings(8, 8, shadow_culling=1)
    with pytest.raises(SceneError, match=r"render settings: shadow_culling: got 1; need True"):
        render_tiny(ball_on_ground(), settings)


def test_region_outside_image():
    with pytest.raises(SceneError, match="render settings: region"):
        render_tiny(ball_on_ground(), RenderSettings(4, 4, region=(2, 2, 3, 3)))


def test_an_image_larger_than_the_machine_is_refused_before_it_is_allocated(monkeypatch):
    """A 65536 x 65536 frame started, and would have needed 64 GiB of float pixels."""
    import core.model.settings

    monkeypatch.setattr(core.model.settings, "machine_memory", lambda: 24 * 2**30)
    settings = RenderSettings(65536, 65536)
    with pytest.raises(SceneError, match=r"width, height: a 65536 x 65536 image needs 64.0 GiB"):
        render_tiny(ball_on_ground(), settings)
    RenderSettings(4096, 4096).validate()  # 0.25 GiB: fine
