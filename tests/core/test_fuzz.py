"""Property-based fuzzing: random scenes of every shape kind, CSG trees up to depth 4,
transforms down to near-singular, extreme materials and lights render at 16 x 16 with no
NaN, no infinity, no exception but `SceneError`, and no hang.

`make test` runs a fixed-seed sample of examples; `make fuzz` runs the same properties with
WHITTED_FUZZ_EXAMPLES (thousands) and a random seed.
"""

import numpy as np
from hypothesis import given
from hypothesis import strategies as st

import core
from tests.support.fuzz_scenes import (
    FUZZ,
    lights,
    render_or_refuse,
    render_settings,
    scenes,
    solids,
)


@FUZZ
@given(scene=scenes(), render_settings=render_settings())
def test_random_scenes_render_finite_or_are_refused(scene, render_settings):
    image = render_or_refuse(scene, render_settings)
    if image is not None:
        assert image.shape == (16, 16, 4)
        assert np.all(np.isfinite(image)), "NaN or infinity in the picture"
        assert np.all(image >= 0.0)


@FUZZ
@given(solid=solids(4), light=lights(), seed=st.integers(0, 999))
def test_random_csg_trees_in_front_of_the_camera(solid, light, seed):
    """A CSG tree (depth up to 4) centred in view, so most examples really hit it."""
    camera = core.Camera(eye=(0.0, -12.0, 0.0), view=(0.0, 1.0, 0.0), up=(0.0, 0.0, 1.0),
                         fovy=60.0)  # fmt: skip
    scene = core.Scene(camera=camera, shapes=[solid], lights=[light], ambient=(0.1,) * 3)
    settings_ = core.RenderSettings(width=16, height=16, tile_size=16, threads=1, max_depth=6,
                                    shadow_samples=2, seed=seed, pixel_samples=1)  # fmt: skip
    image = render_or_refuse(scene, settings_)
    if image is not None:
        assert np.all(np.isfinite(image)) and np.all(image >= 0.0)
