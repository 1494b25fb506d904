"""Kernel variants (core.jit.variants, core.kernels.features): a scene rendered by the variant
compiled without the features it does not use gives the full kernel's pixels, bit for bit.

Three scenes, three variants: one with none of the features (its variant leaves all out),
and two that use between them every feature, each feature in one and left out of the
other. A feature the packed scene uses but `used_features` missed would be left out of
its variant and change the picture; a feature whose code still ran where a scene does not
use it would show as a difference in the scenes that leave it out.
"""

import numpy as np
import pytest

from core import (
    AreaLight,
    Box,
    Camera,
    Cone,
    Csg,
    Cylinder,
    Environment,
    Link,
    Material,
    Mesh,
    PanelLight,
    PointLight,
    RenderSettings,
    Scene,
    ShaderNode,
    Sphere,
    SphereLight,
    SunLight,
    Texture,
    Torus,
    TriangleMesh,
    driver,
    render,
)
from core.compile import compile_scene
from core.compile.features import expected_features, left_out, used_features
from core.jit import variants
from core.kernels.features import FEATURES
from core.kernels.integrator import trace_ray
from core.kernels.material_at_hit import material_at_hit
from core.kernels.render_tile import render_tile
from core.kernels.trace import closest_hit

SIZE = 24


def _placed(x=0.0, y=0.0, z=0.0, size=1.0):
    m = np.diag([*np.broadcast_to(size, 3), 1.0])
    m[:3, 3] = (x, y, z)
    return m


def _basics():
    """Shapes of every kind, the report's lights, a mirror, glass and a texture."""
    checker = np.zeros((4, 4, 3))
    checker[::2, ::2] = checker[1::2, 1::2] = 0.9
    vertices = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], float) - 0.3
    triangles = np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]])
    return [
        Box("Floor", Material(texture=Texture(pixels=checker)), _placed(z=-1.1, size=(4, 4, 0.1))),
        Sphere(
            "Glass", Material(transparency=0.8, reflectivity=0.1), _placed(-1.0, 0.0, -0.5, 0.6)
        ),  # fmt: skip
        Box("Mirror", Material(diffuse=(0.1, 0.1, 0.1), reflectivity=0.8), _placed(0, 3, 0, 0.8)),
        Torus("Torus", Material(diffuse=(0.8, 0.3, 0.2)), _placed(1.2, 0.0, -0.5, 0.5)),
        Mesh(
            "Mesh",
            Material(diffuse=(0.2, 0.8, 0.3)),
            _placed(0.0, -1.0, 0.3, 0.8),
            mesh=TriangleMesh(vertices, triangles),
        ),  # fmt: skip
        Csg(
            "Csg",
            operation="difference",
            left=Box("Block", world_from_object=_placed(size=0.4)),
            right=Cylinder("Bore", world_from_object=_placed(size=0.3)),
            world_from_object=_placed(0.0, 1.0, 0.8),
        ),  # fmt: skip
        Cone("Cone", Material(diffuse=(0.3, 0.3, 0.9)), _placed(-1.2, 1.2, 0.0, 0.4)),
    ]


def _camera():
    return Camera(eye=(0.0, -6.0, 3.0), view=(0.0, 6.0, -3.0), up=(0.0, 0.0, 1.0), fovy=45.0)


def _report_lights():
    return [
        PointLight((2.0, -3.0, 4.0), (0.8, 0.8, 0.8)),
        AreaLight((0.0, 0.0, 4.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.5, 0.5, 0.5)),
    ]


def _settings(**more):
    return RenderSettings(SIZE, SIZE, pixel_samples=2, shadow_samples=2, max_depth=4,
                          environment_samples=2, **more)  # fmt: skip


def plain_scene():
    return Scene(camera=_camera(), shapes=_basics(), lights=_report_lights()), _settings()


def blender_scene():
    """Node materials (one varying by Layer Weight, whose veil lets shadows through by the
    angle; one under a rough clear coat; a translucent sheet lit from behind), Blender's
    lights seen in the mirror, a rough mirror spread over its lobe."""
    facing = ShaderNode("layer_weight", {"Blend": 0.5})
    clear, red = ShaderNode("transparent", {}), ShaderNode("diffuse", {"Color": (0.8, 0.1, 0.1)})
    veil = ShaderNode("mix_shader", {"Fac": Link(facing, "Facing"), "Shader A": Link(clear),
                                     "Shader B": Link(red)})  # fmt: skip
    rough = Material(diffuse=(0.0, 0.0, 0.0), reflectivity=0.9, roughness=0.3)
    paper = ShaderNode("translucent", {"Color": (0.8, 0.7, 0.3)})
    # upright, facing the camera: the lamps above light its back at a slant
    sheet = TriangleMesh(np.array([(-1, 0, -1), (1, 0, -1), (1, 0, 1), (-1, 0, 1)], float),
                         np.array([(0, 2, 1), (0, 3, 2)]))  # fmt: skip
    coated = ShaderNode("principled", {"Base Color": (0.5, 0.05, 0.1), "Metallic": 0.5,
                                       "Coat Weight": 1.0, "Coat Roughness": 0.2,
                                       "Coat Tint": (0.9, 0.8, 0.7)})  # fmt: skip
    shapes = [
        *_basics(),
        Sphere("Veil", Material(surface=veil), _placed(0.5, -0.5, 1.2, 0.5)),
        Box("Rough mirror", rough, _placed(-2.5, 1.0, 0.0, 0.6)),
        Sphere("Car paint", Material(surface=coated), _placed(1.8, 1.5, 0.6, 0.6)),
        Mesh("Paper", Material(surface=paper), _placed(-0.5, -1.5, 0.8, 0.7), mesh=sheet),
    ]
    lights = [
        *_report_lights(),
        PanelLight(centre=(1.0, -1.0, 3.0), power=(300.0, 300.0, 300.0)),
        SphereLight(position=(-1.0, -2.0, 2.0), power=(200.0, 200.0, 200.0), radius=0.3),
    ]
    return Scene(camera=_camera(), shapes=shapes, lights=lights), _settings(glossy_samples=2)


def world_scene():
    """The World's light, caustics of a glass ball under the sun (and of a tinted one that
    absorbs inside), passes and adaptive anti-aliasing."""
    sun = SunLight(name="Sun", direction=(0.3, 0.2, -1.0), irradiance=(2.0, 2.0, 2.0))
    tinted = Material(transparency=1.0, inner_ior=1.45, absorption=(0.2, 1.5, 3.0))
    shapes = [*_basics(), Sphere("Tinted glass", tinted, _placed(1.0, 1.0, -0.4, 0.6))]
    scene = Scene(camera=_camera(), shapes=shapes, lights=[*_report_lights(), sun],
                  environment=Environment(colour=(0.2, 0.3, 0.4)))  # fmt: skip
    settings = _settings(caustics=("reflective", "refractive"), caustic_photons=4000,
                         glass_shadows="blocked", passes=("depth", "normal", "diffuse"),
                         adaptive_threshold=0.01)  # fmt: skip
    return scene, settings


def test_each_scene_uses_the_features_it_was_made_for():
    """The premise of the pixel test: between them the two scenes use every feature, and
    each feature is left out of at least one variant."""
    used = {name: used_features(compile_scene(*make()).packed) for name, make in SCENES.items()}
    assert used["plain"] == frozenset()
    assert used["blender"] == {"nodes", "emitters", "emitters_seen", "varying_shadows", "glossy",
                               "clear_coat", "translucent"}  # fmt: skip
    assert used["world"] == {"emitters", "emitters_seen", "environment", "caustics", "passes",
                             "adaptive", "absorption"}  # fmt: skip
    assert used["blender"] | used["world"] == set(FEATURES)


SCENES = {"plain": plain_scene, "blender": blender_scene, "world": world_scene}


@pytest.mark.parametrize("name", SCENES)
def test_a_variant_renders_its_scene_as_the_full_kernel(name, monkeypatch):
    scene, settings = SCENES[name]()
    compiled = compile_scene(scene, settings)
    kernel = variants.variant(render_tile, left_out(compiled.packed))
    if name != "plain":  # the plain scene's variant may be the one the driver took already
        assert kernel is not render_tile
    monkeypatch.setattr(driver, "tile_kernel", lambda packed: kernel)
    with_variant = render(scene, settings)
    monkeypatch.setattr(driver, "tile_kernel", lambda packed: render_tile)
    with_full = render(scene, settings)
    assert with_full.image.max() > 0.05  # the premise: something to compare
    np.testing.assert_array_equal(with_variant.image, with_full.image)
    assert with_variant.passes.keys() == with_full.passes.keys()
    for pass_name, values in with_full.passes.items():
        np.testing.assert_array_equal(with_variant.passes[pass_name], values, err_msg=pass_name)


def test_a_variant_copies_only_the_kernels_that_read_a_feature():
    everything = frozenset(FEATURES)
    copy = variants.variant(render_tile, everything)
    assert copy is not render_tile
    assert copy.py_func.__qualname__ == f"render_tile__without_{variants.tag(everything)}"
    assert copy.py_func.__globals__["trace_ray"] is variants.variant(trace_ray, everything)
    assert copy.py_func.__globals__["trace_ray"] is not trace_ray
    # the nearest-hit search reads no feature: every variant shares it, compiled once
    assert variants.variant(closest_hit, everything) is closest_hit
    assert copy.py_func.__globals__["trace_ray"].py_func.__globals__["closest_hit"] is closest_hit
    # a feature's call of its own, in a module of its own, is copied with its constant off
    traced = copy.py_func.__globals__["trace_ray"].py_func.__globals__
    assert traced["WITH_PASSES"] is False
    assert traced["material_at_hit"].py_func.__globals__["WITH_NODES"] is False
    assert traced["material_at_hit"] is not material_at_hit
    assert material_at_hit.py_func.__globals__["WITH_NODES"] is True  # the module is untouched
    assert variants.variant(render_tile, everything) is copy  # made once
    assert variants.variant(render_tile, frozenset()) is render_tile


def test_an_unknown_feature_is_refused_by_name():
    with pytest.raises(ValueError, match="volumes"):
        variants.variant(render_tile, frozenset({"volumes"}))


def test_the_driver_takes_a_compiled_full_kernel_over_compiling_a_variant(monkeypatch):
    """The full kernel compiled (or in the cache) and the scene's variant not: the full one
    renders, rather than a compile; a variant compiled renders its scenes."""
    monkeypatch.delenv(driver.FULL_KERNEL_SWITCH, raising=False)  # the suite's (conftest)
    packed = compile_scene(*plain_scene()).packed
    compiled_variant = variants.variant(render_tile, left_out(packed))
    monkeypatch.setattr(driver, "_in_cache", lambda kernel: kernel is render_tile)
    if not compiled_variant.signatures:
        assert driver.tile_kernel(packed) is render_tile
    monkeypatch.setattr(driver, "_in_cache", lambda kernel: kernel is compiled_variant)
    assert driver.tile_kernel(packed) is compiled_variant
    monkeypatch.setenv(driver.FULL_KERNEL_SWITCH, "1")
    assert driver.tile_kernel(packed) is render_tile


def constant_nodes_scene():
    """A Principled-like constant graph (folded into the table: no node programs) and a
    glowing ball, the CS488 lights only."""
    diffuse = ShaderNode("diffuse", {"Color": (0.2, 0.6, 0.2)})
    glow = Material(emission=(2.0, 1.0, 0.5))
    shapes = [*_basics(), Sphere("Folded", Material(surface=diffuse), _placed(2.0, -1.0, 0.5, 0.4)),
              Sphere("Glow", glow, _placed(-2.0, -1.0, 0.5, 0.3))]  # fmt: skip
    return Scene(camera=_camera(), shapes=shapes, lights=_report_lights()), _settings()


def opaque_nodes_scene():
    """A node material that varies over the surface (a noise texture's colour) but lets no
    light through: its shadows do not vary, so its variant has no varying-shadow code."""
    noise = ShaderNode("noise", {"Scale": 4.0})
    textured = ShaderNode("diffuse", {"Color": Link(noise, "Color")})
    shapes = [*_basics(), Sphere("Noisy", Material(surface=textured), _placed(2.0, -1.0, 0.5, 0.4))]
    return Scene(camera=_camera(), shapes=shapes, lights=_report_lights()), _settings()


def sharp_scene_asking_for_glossy_rays():
    """Blender's default Glossy Samples (8) over a scene with no rough surface: a smooth
    metal, folded into the table, and the report's materials."""
    metal = ShaderNode("principled", {"Metallic": 1.0, "Roughness": 0.0})
    shapes = [*_basics(), Sphere("Chrome", Material(surface=metal), _placed(2.0, -1.0, 0.5, 0.4))]
    return Scene(camera=_camera(), shapes=shapes, lights=_report_lights()), _settings(
        glossy_samples=8
    )


@pytest.mark.parametrize("make", [*SCENES.values(), constant_nodes_scene, opaque_nodes_scene,
                                  sharp_scene_asking_for_glossy_rays])  # fmt: skip
def test_the_features_expected_before_packing_hold_those_packing_finds(make):
    """The warm-up compiles the variant of `expected_features` before the scene is packed:
    it must hold every feature the packed scene uses, or the render compiles again."""
    scene, settings = make()
    expected = expected_features(scene, settings)
    used = used_features(compile_scene(scene, settings).packed)
    assert used <= expected, used - expected
    if make is plain_scene:
        assert expected == frozenset()  # and not everything: a variant saves a compile
    if make is opaque_nodes_scene:
        assert expected == used == frozenset({"nodes"})  # its shadows do not vary
    if make is sharp_scene_asking_for_glossy_rays:
        assert expected == used == frozenset()  # no rough surface: no glossy code compiled
