"""Adaptive soft shadows (RenderSettings.adaptive_shadows, core.kernels.shadow_rays): nine
probe rays to each light first, its samples' rays only where the probes disagree.

It is an acceleration with a stated blind spot, so it is checked against the exact
estimate (every sample's ray cast, the same samples) and against the truth where the blind
spot lies:
- a straight shadow edge under a rectangle light (the report's and Blender's): the probes
  include the light's corners, so every partly blocked point is seen: the picture is the
  exact one bit for bit, for a fraction of the shadow rays;
- lights mapped onto a disk or a cone (a sphere, a disk, an ellipse, a sun with an angle):
  the pixels differ only in a penumbra's outer fringe, by no more than the sliver of the
  disk between two rim probes (1.2% of the light) and a sample's share;
- a pole narrower than the light, which the probes straddle: the shadow it should cast is
  missed where all nine pass it; the error against the visibility computed here by
  quadrature is bounded by the pole's share of the light;
- any tiling and render border give the same pixels; a card whose alpha varies (the shadow
  log's replay) casts the same shadow as with every ray.
"""

import numpy as np
import pytest

from core import (
    AreaLight,
    Box,
    Camera,
    Cylinder,
    Material,
    PanelLight,
    RenderSettings,
    Scene,
    SphereLight,
    SpotLight,
    SunLight,
    render,
)
from core.kernels.shadow_log import PROBES

WHITE = Material(diffuse=(1.0, 1.0, 1.0), specular=(0.0, 0.0, 0.0), name="white")
SIZE, VIEW = 32, 6.0  # pixels across, and the floor's metres they cover
SAMPLES = 64


def box(name, low, high):
    """An axis-aligned box from corner `low` to corner `high` (Box is the cube [-1, 1]^3)."""
    low, high = np.asarray(low, float), np.asarray(high, float)
    m = np.diag([*((high - low) / 2.0), 1.0])
    m[:3, 3] = (high + low) / 2.0
    return Box(name, WHITE, m)


FLOOR = box("Floor", (-100, -100, -1), (100, 100, 0))
# A slab from x = 3.5 on, outside the camera's view (x within +-3), 1 m above the floor:
# lights beyond it, low in the sky, cast its straight edge's shadow across the view (from
# 12 m away, a penumbra over x in -1.1..-0.4 and the umbra from there on)
SLAB = box("Slab", (3.5, -50, 1.0), (60, 50, 1.1))


def rendered(lights, shapes, adaptive, **overrides):
    """The floor seen straight down (orthographic, one ray a pixel centre), and the render's
    stats."""
    camera = Camera(eye=(0.0, 0.0, 10.0), view=(0.0, 0.0, -1.0), up=(0.0, 1.0, 0.0),
                    projection="orthographic", ortho_height=VIEW)  # fmt: skip
    settings = RenderSettings(SIZE, SIZE, pixel_samples=1, shadow_samples=SAMPLES,
                              adaptive_shadows=adaptive, **overrides)  # fmt: skip
    result = render(Scene(camera, [FLOOR, *shapes], lights), settings)
    return result.image[..., :3].astype(float), result.stats


def rays_tested(stats):
    """Shadow rays tested against shapes (the others had none in the light's pyramid)."""
    return stats.shadow_rays - stats.shadow_rays_unobstructed


def assert_rays_spent_on_the_penumbra(fast_stats, exact_stats, exact, unblocked):
    """The adaptive render cast 9 rays where the exact one cast 64, and 64 more only in the
    penumbra (pixels neither black nor unblocked), give or take two columns of pixels at
    its edges, where the probes and the samples may see a shadow's edge differently."""
    lit = exact[..., 0]
    penumbra = int(((lit > 0) & (lit < unblocked[..., 0])).sum())
    expected = PROBES / SAMPLES * rays_tested(exact_stats) + SAMPLES * penumbra
    assert abs(rays_tested(fast_stats) - expected) <= SAMPLES * 2 * SIZE, (
        rays_tested(fast_stats),
        expected,
    )


def test_a_straight_shadow_edge_under_a_rectangle_is_the_exact_picture_for_fewer_rays():
    panel = PanelLight(centre=(12.0, 0.0, 3.0), edge_u=(1.5, 0, 0), edge_v=(0, 1.5, 0),
                       power=(400.0,) * 3, name="Panel")  # fmt: skip
    report = AreaLight(centre=(12.0, 0.0, 3.0), edge_u=(1.5, 0, 0), edge_v=(0, 1.5, 0),
                       intensity=(3.0,) * 3)  # fmt: skip
    for light in (panel, report):
        exact, exact_stats = rendered([light], [SLAB], False)
        fast, fast_stats = rendered([light], [SLAB], True)
        unblocked, _ = rendered([light], [], False)
        lit = exact[..., 0]
        assert (lit == unblocked[..., 0]).any() and (lit == 0).any(), "lit floor and umbra"
        np.testing.assert_array_equal(fast, exact)
        assert_rays_spent_on_the_penumbra(fast_stats, exact_stats, exact, unblocked)


ROUND_LIGHTS = {
    "sphere": SphereLight(position=(12.0, 0.0, 3.0), radius=0.75, power=(800.0,) * 3),
    "spot disk": SpotLight(
        position=(12.0, 0.0, 3.0), radius=0.75, power=(800.0,) * 3, spot_size=170.0
    ),  # fmt: skip
    "ellipse": PanelLight(
        centre=(12.0, 0.0, 3.0),
        edge_u=(1.5, 0, 0),
        edge_v=(0, 1.5, 0),
        shape="ellipse",
        power=(400.0,) * 3,
    ),  # fmt: skip
    "sun with angle": SunLight(direction=(-3.0, 0.0, -1.0), angle=5.0, irradiance=(3.0,) * 3),
}


@pytest.mark.parametrize("name", ROUND_LIGHTS)
def test_round_lights_differ_only_by_the_sliver_between_rim_probes(name):
    light = ROUND_LIGHTS[name]
    exact, exact_stats = rendered([light], [SLAB], False)
    fast, fast_stats = rendered([light], [SLAB], True)
    unblocked, _ = rendered([light], [], False)
    lit = exact.max(axis=2)
    assert ((lit > 0) & (lit < 0.99 * unblocked.max(axis=2))).any(), "a penumbra in view"
    # A straight edge cutting off the disk between two rim probes hides 1.2% of it; the
    # samples in that sliver are 1.2% of them give or take one
    bound = (0.012 + 1.0 / SAMPLES) * unblocked + 1e-6
    assert (np.abs(fast - exact) <= bound).all(), np.abs(fast - exact).max()
    assert (fast != exact).mean() < 0.1
    assert_rays_spent_on_the_penumbra(fast_stats, exact_stats, exact, unblocked)


def pole_visibility(points, light_centre, half, pole_x, pole_radius, pole_top):
    """The share of the square light (centre, half-width `half`, facing down) each floor
    point sees past a vertical pole (axis x = pole_x, y = 0, from the floor to pole_top),
    by quadrature over the light: 128 x 128 points."""
    u = (np.arange(128) + 0.5) / 128 * 2 * half - half
    lx, ly = np.meshgrid(light_centre[0] + u, light_centre[1] + u)
    seen = np.empty(len(points))
    for i, (px, py) in enumerate(points):
        # Where the segment from the point to each light point passes the pole's axis line
        # nearest: distance in the xy-plane from (pole_x, 0) to the segment's shadow, and the
        # height there
        dx, dy = lx - px, ly - py
        t = np.clip(((pole_x - px) * dx + (0.0 - py) * dy) / (dx * dx + dy * dy), 0, 1)
        gap = np.hypot(px + t * dx - pole_x, py + t * dy)
        height = t * light_centre[2]
        seen[i] = 1.0 - np.mean((gap < pole_radius) & (height < pole_top))
    return seen


def test_a_pole_narrower_than_the_light_is_missed_only_where_the_probes_straddle_it():
    # A 2 m square light 3 m up; a pole of 0.1 m radius, 2.5 m tall, at x = 0: seen from
    # the floor under the light, the probes (1 m apart on the light) pass either side of it
    panel = PanelLight(centre=(0.0, 0.0, 3.0), edge_u=(2.0, 0, 0), edge_v=(0, 2.0, 0),
                       power=(400.0,) * 3)  # fmt: skip
    pole_matrix = np.diag([0.1, 0.1, 1.25, 1.0])
    pole_matrix[:3, 3] = (1.5, 0.0, 1.25)
    pole = Cylinder("Pole", WHITE, pole_matrix)
    exact, _ = rendered([panel], [pole], False)
    fast, _ = rendered([panel], [pole], True)
    unblocked, _ = rendered([panel], [], False)
    centres = ((np.arange(SIZE) + 0.5) / SIZE - 0.5) * VIEW
    x, y = np.meshgrid(centres, -centres)
    seen = pole_visibility(np.stack([x.ravel(), y.ravel()], 1), (0.0, 0.0, 3.0), 1.0, 1.5,
                           0.1, 2.5).reshape(SIZE, SIZE)  # fmt: skip
    visible_floor = np.hypot(x - 1.5, y) > 0.1  # not the pole's own top
    exact_share = (exact[..., 0] / unblocked[..., 0])[visible_floor]
    fast_share = (fast[..., 0] / unblocked[..., 0])[visible_floor]
    blocked = (1.0 - seen)[visible_floor]
    # The exact estimate: the truth within the samples' noise (and a pixel's spread)
    noise = np.abs(exact_share - (1.0 - blocked)).max()
    assert noise < 0.1
    # The adaptive one misses shadow (never adds any), only where there is shadow to miss,
    # and never more than there is
    missed = fast_share - exact_share
    assert missed.min() >= 0.0
    assert (missed > 0.02).any(), "the blind spot: the probes straddle the pole's shadow"
    assert (missed[blocked == 0.0] == 0.0).all()
    assert (missed <= blocked + noise).all()


def test_any_tiling_and_border_gives_the_same_pixels():
    panel = PanelLight(centre=(12.0, 0.0, 3.0), edge_u=(1.5, 0, 0), edge_v=(0, 1.5, 0),
                       power=(400.0,) * 3)  # fmt: skip
    light = ROUND_LIGHTS["sphere"]
    whole, _ = rendered([panel, light], [SLAB], True, tile_size=32)
    tiled, _ = rendered([panel, light], [SLAB], True, tile_size=5, threads=2)
    np.testing.assert_array_equal(tiled, whole)
    border, _ = rendered([panel, light], [SLAB], True, region=(7, 3, 11, 20))
    np.testing.assert_array_equal(border[3:23, 7:18], whole[3:23, 7:18])
