"""The automatic photon budget (core.compile.photon_budget): the caustics in the frame decide
how many photons are traced. Checked against what the rule says, the camera's own rays and
the closed form of the ball lens (tests/core/test_caustics.py's exact tracer), not against
pictures Whitted made earlier:

- the pilot's photons are projected where the camera's rays (core.kernels.camera) see them;
- a caustic out of sight gets the fewest photons, one filling the frame more than the noise
  rule's, and no budget passes the camera rays' cap or the settings' ceiling;
- the budget, and so the photons, are the same for any border, tiles and threads;
- at the automatic budget the ball lens's floor agrees with the exact tracer within 3%.
"""

import math
from dataclasses import replace

import numpy as np
import pytest

from core import Camera, RenderSettings, SceneError
from core.compile import compile_scene
from core.compile.photon_budget import FEWEST, NOISE, PILOT_PHOTONS, automatic_budget, screen_points
from core.driver import render
from core.kernels.camera import ray_through
from tests.benchmarks.bench_caustics import ball_lens_scene
from tests.core.test_caustics import N, _ball_on_floor_light, _floor_picture, _sun

CAUSTICS = ("reflective", "refractive")


def _settings(size=64, pixel_samples=1, **more):
    return RenderSettings(size, size, pixel_samples=pixel_samples, glass_shadows="blocked",
                          caustics=CAUSTICS, max_depth=12, **more)  # fmt: skip


def _seen_from(view, **camera):
    """The ball lens seen from straight above, its floor `view` m across."""
    base = ball_lens_scene()
    settings = dict(projection="orthographic", ortho_height=view) | camera
    return replace(base, camera=Camera(eye=(-1.5, 0.0, 10.0), view=(0.0, 0.0, -1.0),
                                       up=(0.0, 1.0, 0.0), **settings))  # fmt: skip


@pytest.mark.parametrize("projection", ["perspective", "orthographic"])
def test_points_project_where_the_cameras_rays_see_them(projection):
    camera = Camera(eye=(1.0, -2.0, 3.0), view=(-0.3, 0.8, -0.4), up=(0.0, 0.0, 1.0),
                    fovy=40.0, projection=projection, ortho_height=3.0)  # fmt: skip
    scene = replace(ball_lens_scene(), camera=camera)
    settings = RenderSettings(120, 80)
    frame = compile_scene(scene, settings).packed.frame
    rng = np.random.default_rng(1)
    pixels = rng.uniform((0.0, 0.0), (120.0, 80.0), size=(50, 2))
    points = []
    for (x, y), distance in zip(pixels, rng.uniform(0.5, 20.0, 50), strict=True):
        origin, direction = ray_through(frame, 120, 80, x, y, 0.0, 0.0)
        points.append(np.asarray(origin) + distance * np.asarray(direction))
    behind = 2.0 * frame.camera[0] - points[0]  # the first point mirrored through the eye
    if projection == "orthographic":
        behind = points[0] - 30.0 * frame.camera[1]
    outside = points[0] + 50.0 * frame.camera[2]  # far to the right of the frame
    seen = screen_points(frame, 120, 80, np.array([*points, behind, outside]))
    np.testing.assert_allclose(seen, pixels, atol=1e-6)  # the last two are not in the frame


def test_a_caustic_out_of_sight_gets_the_fewest_photons():
    away = _seen_from(4.0, projection="perspective")
    away = replace(away, camera=replace(away.camera, view=(0.0, 0.0, 1.0)))  # at the sky
    budget = compile_scene(away, _settings()).caustics.budget
    assert (budget.pilot_seen, budget.photons, budget.reason) == (0, FEWEST, "fewest")


def test_a_caustic_filling_the_frame_gets_more_photons_than_one_seen_small():
    """Seen from afar the noise rule sets the budget: about (1 / NOISE^2)^2 photons stored.
    Seen close, the disks would blur it over more pixels than the rule allows: more."""
    settings = _settings(200, pixel_samples=4)  # 640,000 camera rays: room above the rules
    far = compile_scene(_seen_from(16.0), settings).caustics
    near = compile_scene(_seen_from(2.0), settings).caustics
    print(f"far {far.budget}, near {near.budget}")
    assert far.budget.reason == "noise"
    stored = (1.0 / NOISE**2) ** 2
    assert stored <= far.stored <= 1.1 * stored
    assert near.budget.reason == "blur" and near.traced > 1.5 * far.traced


def test_a_glint_too_sharp_to_blur_gets_the_noise_rules_photons():
    """A pilot whose photons land within a millimetre (a mirror's glint seen from afar): its
    disks blur under a pixel at any count, so the bisection on the blur runs down to a
    single photon traced; the budget is still the noise rule's (a math domain error once,
    seen in four Blender tests)."""
    settings = _settings(200, pixel_samples=4)
    frame = compile_scene(_seen_from(4.0), settings).packed.frame
    rng = np.random.default_rng(3)
    glint = np.array([-1.5, 0.0, 0.0]) + rng.normal(0.0, 1e-4, size=(8000, 3))
    budget = automatic_budget(frame, settings, glint, PILOT_PHOTONS)
    stored = (1.0 / NOISE**2) ** 2 * PILOT_PHOTONS / 8000
    assert budget.reason == "noise" and stored <= budget.photons <= 1.1 * stored
    assert budget.pilot_seen == 8000 and budget.blur_pixels < 0.1


def test_no_budget_passes_the_camera_rays_or_the_ceiling():
    small = compile_scene(_seen_from(4.0), _settings(64)).caustics
    # 4,096 camera rays: raised to the fewest
    assert small.traced == FEWEST and small.budget.reason == "camera rays"
    # 200 x 200 camera rays: the noise rule would trace 190,000
    capped = compile_scene(_seen_from(4.0), _settings(200)).caustics
    assert capped.traced == 40_000 and capped.budget.reason == "camera rays"
    ceiling = compile_scene(_seen_from(4.0), _settings(200, caustic_photons_max=30_000)).caustics
    assert ceiling.traced <= 30_000 and ceiling.budget.reason == "most"
    # rounded to two figures, but never past the cap: 180 x 180 rays are 32,400, not 33,000
    odd = compile_scene(_seen_from(4.0), _settings(180)).caustics
    assert odd.traced == 180 * 180 and odd.budget.reason == "camera rays"


def test_the_budget_and_photons_are_the_same_for_any_border_tiles_and_threads():
    whole = compile_scene(_seen_from(4.0), _settings(96))
    part = compile_scene(_seen_from(4.0), _settings(96, region=(10, 20, 40, 30), tile_size=8,
                                                    threads=1))  # fmt: skip
    assert whole.caustics.budget == part.caustics.budget
    a, b = whole.packed.lights, part.packed.lights
    np.testing.assert_array_equal(a.photon_position, b.photon_position)
    np.testing.assert_array_equal(a.photon_power, b.photon_power)


def test_at_the_automatic_budget_the_ball_lens_matches_the_exact_tracer():
    """tests/core/test_caustics.py's check of the issue's ball, at the automatic budget."""
    from core import Material, Sphere
    from tests.core.test_caustics import _hidden, _placed

    radius, centre = 1.0, (0.0, 0.0, 1.5)
    ball = _hidden(Sphere("Ball", Material(diffuse=(0.0, 0.0, 0.0), transparency=1.0,
                                           inner_ior=N), _placed(*centre)))  # fmt: skip
    sun, view, middle = _sun(45.0), 4.0, (-1.5, 0.0)
    settings = _settings(100, caustic_photons="auto")
    image, _, _ = _floor_picture([ball], sun, settings, centre=middle, view=view)
    region = (middle[0] - 2.0, middle[0] + 2.0, -2.0, 2.0)
    direct = math.cos(math.radians(45.0))
    open_power = direct * view * view
    arrived, blocked = _ball_on_floor_light(centre, radius, sun.direction, region)
    expected = (open_power - blocked + arrived) / open_power
    measured = image.mean() / (direct / math.pi)
    print(f"automatic budget: region {measured:.4f} against {expected:.4f}")
    assert math.isclose(measured, expected, rel_tol=0.03)


def test_the_summary_line_says_the_count_was_automatic():
    result = render(_seen_from(4.0), _settings(24))
    assert "photons traced (automatic)" in result.stats.summary()
    fixed = render(_seen_from(4.0), _settings(24, caustic_photons=30_000))
    assert "30,000 photons traced," in fixed.stats.summary()


@pytest.mark.parametrize(
    "field, value, words",
    [
        ("caustic_photons", "lots", 'use a count from 0 to 10,000,000 or "auto"'),
        ("caustic_photons", -1, "use a whole number >= 0"),
        ("caustic_photons_max", 0, "use a whole number >= 1"),
    ],
)
def test_a_bad_budget_is_refused_in_the_settings_terms(field, value, words):
    with pytest.raises(SceneError) as raised:
        _settings(**{field: value}).validate()
    assert field in str(raised.value) and words in str(raised.value)
