"""Area-light shadow culling (core.kernels.light_pyramid) is exact: the pyramid test never
drops a box that meets the pyramid, and a render with culling gives the same bits as one
that tests every shape, on fuzzed scenes of every shape kind, glass and shapes that cast no
shadow included. Also: a shape that casts no shadow lets the light through, by the formula."""

import dataclasses

import numpy as np
from hypothesis import given
from hypothesis import strategies as st

import core
from core.compile.frame import SHADOW_CULLING_MIN_SAMPLES
from core.kernels.light_pyramid import PYRAMID_ROWS, box_meets_pyramid, build_pyramid
from tests.support.fuzz_scenes import FUZZ, lights, materials, open_meshes, render_or_refuse, solids
from tests.support.scenes import GROUND_KD, ground, look_down

RNG = np.random.default_rng(7)


def random_pyramid(rng):
    apex = rng.normal(size=3) * 5.0
    centre = rng.normal(size=3) * 5.0
    edge_u, edge_v = rng.normal(size=3) * 2.0, rng.normal(size=3) * 2.0
    pyramid = np.zeros((PYRAMID_ROWS, 4))
    build_pyramid(pyramid, tuple(apex), tuple(centre), tuple(edge_u), tuple(edge_v))
    corners = [centre + su * edge_u / 2 + sv * edge_v / 2 for su in (-1, 1) for sv in (-1, 1)]
    return pyramid, np.array([apex, *corners])


def test_boxes_around_points_of_the_pyramid_are_never_culled():
    """Points on segments from the apex to the light (where shadow rays run), boxes down to
    a hair around them: every one is kept."""
    for _ in range(200):
        pyramid, vertices = random_pyramid(RNG)
        weights = RNG.dirichlet(np.ones(5), size=50)
        points = weights @ vertices
        for point, half in zip(points, 10.0 ** RNG.uniform(-9, 1, size=50), strict=True):
            box = np.concatenate([point - half, point + half])[None, :]
            assert box_meets_pyramid(pyramid, box, 0)


def test_boxes_far_outside_the_pyramid_are_culled():
    """The test can fail: boxes beyond a face plane, or off to the side, are dropped."""
    apex, centre = (0.0, 0.0, 0.0), (0.0, 0.0, 10.0)
    pyramid = np.zeros((PYRAMID_ROWS, 4))
    build_pyramid(pyramid, apex, centre, (2.0, 0.0, 0.0), (0.0, 2.0, 0.0))
    beside = np.array([[3.0, 3.0, 4.0, 4.0, 4.0, 6.0]])  # within the bounding box's z only
    beyond_light = np.array([[-1.0, -1.0, 11.0, 1.0, 1.0, 12.0]])
    behind_apex = np.array([[-1.0, -1.0, -3.0, 1.0, 1.0, -1.0]])
    off_a_side = np.array([[0.8, -0.1, 1.0, 0.9, 0.1, 2.0]])  # inside the bounding box
    for box in (beside, beyond_light, behind_apex, off_a_side):
        assert not box_meets_pyramid(pyramid, box, 0)
    inside = np.array([[-0.1, -0.1, 4.0, 0.1, 0.1, 5.0]])
    assert box_meets_pyramid(pyramid, inside, 0)


def segment_meets_sphere(o, p, centre, radius):
    """Whether the segment o..p passes through the sphere (closed form, in numpy)."""
    d = p - o
    t = np.clip(np.dot(centre - o, d) / np.dot(d, d), 0.0, 1.0)
    return np.linalg.norm(o + t * d - centre) < radius


def test_every_sphere_a_segment_to_the_light_meets_is_listed():
    """Spheres placed so that segments from the shading point to the light's corners and
    edges (the pyramid's own faces, where culling is most at risk) just clip them: each such
    sphere must be among the candidates."""
    from core.kernels.light_pyramid import MAX_CANDIDATES, pyramid_candidates
    from tests.support.probe import packed_shapes

    rng = np.random.default_rng(11)
    for _ in range(60):
        pyramid, vertices = random_pyramid(rng)
        apex, corners = vertices[0], vertices[1:]
        spheres, hits = [], []
        for _ in range(12):
            a, b = corners[rng.integers(4)], corners[rng.integers(4)]
            target = a + rng.uniform() * (b - a)  # on the light's boundary
            point = apex + rng.uniform(0.05, 0.95) * (target - apex)
            radius = 10.0 ** rng.uniform(-3, 0)
            # Centre off the segment by just under the radius: the segment clips the rim
            side = np.cross(target - apex, rng.normal(size=3))
            centre = point + side / np.linalg.norm(side) * radius * rng.uniform(0.9, 0.999)
            spheres.append(core.Sphere(f"s{len(spheres)}", core.Material(),
                                       _place(centre, radius)))  # fmt: skip
            hits.append(segment_meets_sphere(apex, target, centre, radius))
        packed = packed_shapes(*spheres)
        candidates = np.zeros(MAX_CANDIDATES, np.int32)
        count = pyramid_candidates(packed.geometry, pyramid, candidates, np.zeros(128, np.int32))
        listed = set(candidates[:count].tolist())
        assert all(k in listed for k, hit in enumerate(hits) if hit)


def _place(centre, radius):
    m = np.diag([radius, radius, radius, 1.0])
    m[:3, 3] = centre
    return m


def ball_over_ground(casts_shadows=True):
    place = _lift(2.0) @ np.diag([0.5, 0.5, 0.5, 1.0])
    red = core.Material(diffuse=(0.9, 0.1, 0.1))
    ball = core.Sphere("Ball", red, place, casts_shadows=casts_shadows)
    return [ground(), ball]


def _lift(z):
    m = np.eye(4)
    m[2, 3] = z
    return m


def test_a_shape_that_casts_no_shadow_lets_the_light_through():
    """Under a point light straight above the ball, the ground below it is lit exactly by
    the formula when the ball casts no shadow, and gets ambient only when it does."""
    light = core.PointLight((0.0, 0.0, 6.0), (30.0, 30.0, 30.0), (1.0, 0.0, 0.0))
    camera = core.Camera(eye=(0.0, 0.0, 12.0), view=(0.0, 0.0, -1.0), up=(0.0, 1.0, 0.0),
                         fovy=20.0)  # fmt: skip
    settings = core.RenderSettings(41, 41, pixel_samples=1, max_depth=0)
    pixels = {}
    for casts in (True, False):
        scene = core.Scene(camera, ball_over_ground(casts), [light], ambient=(0.1,) * 3)
        pixels[casts] = core.render(scene, settings).image
    # The ground seen beside the ball, in the ball's shadow cone: find it as a ground pixel
    # that differs between the two renders
    differs = np.any(pixels[True][..., :3] != pixels[False][..., :3], axis=2)
    assert differs.sum() > 10
    lit, shadowed = pixels[False][differs][:, :3], pixels[True][differs][:, :3]
    np.testing.assert_allclose(shadowed, np.broadcast_to(np.array(GROUND_KD) * 0.1, shadowed.shape),
                               rtol=1e-6)  # fmt: skip
    assert np.all(lit > np.array(GROUND_KD) * 0.1 * 2)


def test_culling_answers_most_shadow_rays_without_a_test_and_changes_no_pixel():
    """A ball over the ground under a square area light: most ground points have nothing
    between them and the light."""
    light = core.AreaLight((0.0, 0.0, 6.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (30.0,) * 3,
                           (1.0, 0.0, 0.0))  # fmt: skip
    scene = core.Scene(look_down(), ball_over_ground(), [light], ambient=(0.1,) * 3)
    settings = core.RenderSettings(48, 36, pixel_samples=2, shadow_samples=9, threads=1)
    culled = core.render(scene, settings)
    tested = core.render(scene, dataclasses.replace(settings, shadow_culling=False))
    assert np.array_equal(culled.image, tested.image)
    assert culled.stats.shadow_rays == tested.stats.shadow_rays
    assert tested.stats.shadow_rays_unobstructed == 0
    assert culled.stats.shadow_rays_unobstructed > 0.5 * culled.stats.shadow_rays
    # With fewer shadow rays per light than listing pays for, every shape is tested
    few = core.render(scene, dataclasses.replace(settings, shadow_samples=4))
    assert few.stats.shadow_rays_unobstructed == 0


@st.composite
def shadowed_scenes(draw):
    """Up to eight shapes of every kind (CSG trees, glass, open meshes, some casting no
    shadow) in front of a fixed camera, under one to three area lights and maybe others."""
    shapes = draw(st.lists(st.one_of(solids(2), open_meshes()), min_size=1, max_size=8))
    for shape in shapes:
        shape.casts_shadows = draw(st.integers(0, 4)) > 0
    edge = st.tuples(*[st.floats(-4.0, 4.0)] * 3)
    area = st.builds(
        core.AreaLight, st.tuples(st.floats(-6.0, 6.0), st.floats(-6.0, 6.0), st.floats(2, 9)),
        edge, edge, st.just((20.0, 20.0, 20.0)), st.just((1.0, 0.0, 0.0)),
    )  # fmt: skip
    chosen = draw(st.lists(area, min_size=1, max_size=3)) + draw(st.lists(lights(), max_size=1))
    camera = core.Camera(eye=(0.0, -14.0, 4.0), view=(0.0, 14.0, -4.0), up=(0.0, 0.0, 1.0),
                         fovy=55.0)  # fmt: skip
    return core.Scene(camera, shapes, chosen, ambient=(0.05,) * 3, background=(0.1,) * 3)


@FUZZ
@given(scene=shadowed_scenes(), material=materials(), seed=st.integers(0, 999))
def test_culled_shadow_rays_give_the_same_bits_as_testing_every_shape(scene, material, seed):
    scene.shapes.append(core.Box("Floor", material, _lift(-5.0) @ np.diag([8.0, 8.0, 0.2, 1.0])))
    settings = core.RenderSettings(
        width=20, height=16, tile_size=8, threads=1, max_depth=4, pixel_samples=1,
        shadow_samples=SHADOW_CULLING_MIN_SAMPLES + seed % 5, seed=seed,
    )  # fmt: skip
    culled = render_or_refuse(scene, settings)
    tested = render_or_refuse(scene, dataclasses.replace(settings, shadow_culling=False))
    assert (culled is None) == (tested is None)
    if culled is not None:
        assert np.array_equal(culled, tested, equal_nan=True)


def test_a_pyramid_holding_more_shapes_than_the_list_falls_back_to_every_shape():
    """Forty small balls between the ground and the light: more than MAX_CANDIDATES meet
    most pyramids, which then test every shape along each ray; the same bits as without
    culling."""
    from core.kernels.light_pyramid import MAX_CANDIDATES, TRAVERSE_ALL, pyramid_candidates
    from tests.support.probe import packed_shapes

    rng = np.random.default_rng(5)
    centres = [(*rng.uniform(-0.3, 0.3, 2), 3.0 + k * 0.05) for k in range(MAX_CANDIDATES + 8)]
    balls = [core.Sphere(f"b{k}", core.Material(), _place(c, 0.04)) for k, c in enumerate(centres)]
    # The ground under the balls sees them all in its pyramid: the list overflows
    pyramid = np.zeros((PYRAMID_ROWS, 4))
    build_pyramid(pyramid, (0.0, 0.0, 0.001), (0.0, 0.0, 6.0), (2.0, 0.0, 0.0), (0.0, 2.0, 0.0))
    candidates = np.zeros(MAX_CANDIDATES, np.int32)
    stack = np.zeros(128, np.int32)
    assert pyramid_candidates(packed_shapes(*balls).geometry, pyramid, candidates, stack) == (
        TRAVERSE_ALL
    )
    light = core.AreaLight((0.0, 0.0, 6.0), (2.0, 0.0, 0.0), (0.0, 2.0, 0.0), (30.0,) * 3,
                           (1.0, 0.0, 0.0))  # fmt: skip
    scene = core.Scene(look_down(), [ground(), *balls], [light], ambient=(0.1,) * 3)
    settings = core.RenderSettings(24, 18, pixel_samples=1, shadow_samples=8, threads=1)
    culled = core.render(scene, settings)
    tested = core.render(scene, dataclasses.replace(settings, shadow_culling=False))
    assert np.array_equal(culled.image, tested.image)
