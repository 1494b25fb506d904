"""Area-light shadow culling is exact on every sample scene: each scene of each sample file,
exported as a render sees it, renders to the same bits with culling on and off. Point lights
are turned into small area lights first, so that every scene (glass, mirrors, CSG, textures,
the teapot) casts culled shadow rays."""

import dataclasses
import sys

import numpy as np
import pytest

import core
from tests.blender.conftest import ROOT
from tests.support.render_view import export_scenes

pytestmark = pytest.mark.bpy
SAMPLES = sorted((ROOT / "sample_blends").glob("*.blend"))


def as_area_light(light):
    """A point light as a square area light of side 0.3 around it, facing down."""
    if not isinstance(light, core.PointLight):
        return light
    return core.AreaLight(light.position, (0.3, 0.0, 0.0), (0.0, 0.3, 0.0), light.intensity,
                          light.attenuation, name=light.name)  # fmt: skip


@pytest.mark.parametrize("path", SAMPLES, ids=[p.stem for p in SAMPLES])
def test_culling_changes_no_pixel_of_any_sample_scene(bpy_with_whitted, path):
    bpy = bpy_with_whitted
    bpy.ops.wm.open_mainfile(filepath=str(path))
    for name, scene, settings in export_scenes(bpy, sys.modules["whitted.export"]):
        scene.lights = [as_area_light(light) for light in scene.lights]
        width = 40
        small = dataclasses.replace(
            settings, width=width, height=max(1, width * settings.height // settings.width),
            region=None, pixel_samples=1, shadow_samples=8, threads=2,
        )  # fmt: skip
        culled = core.render(scene, small)
        tested = core.render(scene, dataclasses.replace(small, shadow_culling=False))
        assert np.array_equal(culled.image, tested.image), f"{path.name}, scene '{name}'"
        assert culled.stats.shadow_rays == tested.stats.shadow_rays
        if name == "Final Scene":
            # Most of the room has nothing between it and the light
            share = culled.stats.shadow_rays_unobstructed / culled.stats.shadow_rays
            assert share > 0.5, share
