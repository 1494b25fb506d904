"""Hypothesis strategies for random scenes (shapes of every kind, CSG trees, near-singular
transforms, extreme materials and lights, render settings), the shared example budget
(WHITTED_FUZZ_EXAMPLES), and a render that fails on a hang. Used by tests/core/test_fuzz.py
and the shadow-culling tests."""

import functools
import os
from concurrent.futures import ThreadPoolExecutor

import numpy as np
from hypothesis import HealthCheck, settings
from hypothesis import strategies as st

import core
from tests.support.meshes import icosphere

EXAMPLES = int(os.environ.get("WHITTED_FUZZ_EXAMPLES", "40"))
DERANDOMIZE = "WHITTED_FUZZ_EXAMPLES" not in os.environ
# Far more than a 16 x 16 render of a few shapes needs; past it, the render is a hang
HANG_S = 60.0

FUZZ = settings(
    max_examples=EXAMPLES,
    derandomize=DERANDOMIZE,
    deadline=None,
    suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large],
    database=None,
)

unit = st.floats(0.0, 1.0)
colour = st.tuples(unit, unit, unit)
coordinate = st.floats(-6.0, 6.0)
point = st.tuples(coordinate, coordinate, coordinate)
# Log-uniform scales, sometimes at the edge of what a transform may be
scale = st.one_of(
    st.floats(-3.0, 3.0).map(lambda e: 10.0**e),
    st.sampled_from([1e-9, 1e-12, 1e-13, 0.0, 1e6, 1e9]),
)


@st.composite
def transforms(draw):
    """A random affine matrix: rotation x scale x shear, translated; near-singular ones too
    (a transform too close to singular must be refused with a SceneError)."""
    seed = draw(st.integers(0, 2**32 - 1))
    rng = np.random.default_rng(seed)
    q, _ = np.linalg.qr(rng.normal(size=(3, 3)))
    scales = np.array([draw(scale) for _ in range(3)])
    shear = np.eye(3)
    if draw(st.booleans()):
        shear[0, 1], shear[1, 2] = rng.normal(size=2) * draw(st.sampled_from([0.1, 1.0, 100.0]))
    m = np.eye(4)
    m[:3, :3] = q @ np.diag(scales) @ shear
    m[:3, 3] = draw(point)
    if draw(st.integers(0, 40)) == 0:
        m[draw(st.integers(0, 2)), draw(st.integers(0, 3))] = np.nan
    return m


ior = st.one_of(
    st.floats(1.0, 3.0),
    st.sampled_from([1.0, 1.0 + 1e-12, 1.0 + 1e-6, 1.0 - 1e-6, 0.999, 2.42]),
)
shininess = st.one_of(st.floats(0.0, 200.0), st.sampled_from([0.0, 1e-6, 1e4, 1e6, 1e12, 1e300]))


@st.composite
def materials(draw):
    texture = None
    if draw(st.integers(0, 4)) == 0:
        size = draw(st.tuples(st.integers(1, 4), st.integers(1, 4)))
        pixels = np.random.default_rng(draw(st.integers(0, 99))).random((*size, 3))
        texture = core.Texture(pixels=pixels.astype(np.float32))
    return core.Material(
        diffuse=draw(colour), specular=draw(colour), shininess=draw(shininess),
        reflectivity=draw(unit), transparency=draw(unit), outer_ior=draw(ior),
        inner_ior=draw(ior), texture=texture,
    )  # fmt: skip


ANALYTIC = [core.Sphere, core.Box, core.Cylinder, core.Cone]


@st.composite
def solids(draw, depth):
    """Any shape that can be a CSG operand: analytic, torus, a closed mesh, or a Csg node of
    lower depth."""
    kind = draw(st.integers(0, 6 if depth > 0 else 5))
    common = dict(name=f"s{draw(st.integers(0, 999))}", material=draw(materials()),
                  world_from_object=draw(transforms()))  # fmt: skip
    if kind < 4:
        return ANALYTIC[kind](**common)
    if kind == 4:
        radii = st.floats(1e-4, 3.0)
        return core.Torus(**common, major_radius=draw(radii), minor_radius=draw(radii))
    if kind == 5:
        return core.Mesh(**common, mesh=BALL)
    operation = draw(st.sampled_from(["union", "intersection", "difference"]))
    return core.Csg(**common, operation=operation, left=draw(solids(depth - 1)),
                    right=draw(solids(depth - 1)))  # fmt: skip


BALL = core.TriangleMesh(*icosphere(1), smooth=True)


@st.composite
def open_meshes(draw):
    """A triangle soup, degenerate triangles included (fine outside CSG)."""
    count = draw(st.integers(1, 12))
    rng = np.random.default_rng(draw(st.integers(0, 999)))
    vertices = rng.normal(size=(count + 2, 3))
    if draw(st.booleans()):
        vertices[1] = vertices[0]  # zero-area triangles
    triangles = rng.integers(0, count + 2, size=(count, 3))
    smooth = draw(st.booleans())
    mesh = core.TriangleMesh(vertices, triangles, smooth=smooth)
    return core.Mesh(name="soup", material=draw(materials()),
                     world_from_object=draw(transforms()), mesh=mesh)  # fmt: skip


@st.composite
def lights(draw):
    kind = draw(st.integers(0, 2))
    intensity = draw(st.tuples(*[st.floats(0.0, 100.0)] * 3))
    attenuation = draw(st.one_of(
        st.tuples(*[st.floats(0.0, 2.0)] * 3), st.sampled_from([(0.0, 0.0, 0.0), (1e-9, 0, 0)])
    ))  # fmt: skip
    if kind == 0:
        return core.PointLight(draw(point), intensity, attenuation)
    if kind == 1:
        return core.DirectionalLight(draw(point), intensity)
    edge = st.tuples(*[st.floats(-3.0, 3.0)] * 3)
    return core.AreaLight(draw(point), draw(edge), draw(edge), intensity, attenuation)


@st.composite
def scenes(draw):
    shapes = draw(st.lists(st.one_of(solids(4), open_meshes()), min_size=0, max_size=4))
    camera = core.Camera(
        eye=draw(point), view=draw(point), up=draw(point),
        fovy=draw(st.one_of(st.floats(1e-3, 179.0), st.sampled_from([0.0, 180.0]))),
        aperture_radius=draw(st.sampled_from([0.0, 0.0, 0.1, 2.0])),
        focal_distance=draw(st.floats(0.1, 20.0)),
    )  # fmt: skip
    return core.Scene(
        camera=camera, shapes=shapes, lights=draw(st.lists(lights(), max_size=3)),
        ambient=draw(colour), background=draw(colour),
    )  # fmt: skip


@st.composite
def render_settings(draw):
    return core.RenderSettings(
        width=16, height=16, tile_size=8, threads=1,
        max_depth=draw(st.integers(0, 12)), pixel_samples=draw(st.integers(1, 2)),
        pixel_sampling=draw(st.sampled_from(["grid", "jittered"])),
        shadow_samples=draw(st.integers(1, 4)),
        shadow_sampling=draw(st.sampled_from(["stratified", "uniform"])),
        seed=draw(st.integers(0, 2**31 - 1)),
    )  # fmt: skip


@functools.cache
def _compile_once():
    """Compile (or load) the kernels before any render is timed: a cold compile takes longer
    than HANG_S."""
    core.render(core.Scene(shapes=[core.Sphere()]), core.RenderSettings(width=2, height=2))


def render_or_refuse(scene, render_settings):
    """The image, or None when validation refused the scene with a SceneError; fails on a
    hang (the render runs on its own thread and must finish within HANG_S)."""
    _compile_once()
    pool = ThreadPoolExecutor(max_workers=1)
    future = pool.submit(core.render, scene, render_settings)
    try:
        return future.result(timeout=HANG_S).image
    except core.SceneError as error:
        assert str(error)  # a message naming the object and field
        return None
    finally:
        pool.shutdown(wait=False)  # after a hang, leave the stuck thread behind
