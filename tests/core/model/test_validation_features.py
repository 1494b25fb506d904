"""Bad input for the renderer's features: each raises SceneError naming object and field and
saying what is valid, before any rendering."""

import numpy as np
import pytest

from core import (
    AreaLight,
    Camera,
    Material,
    Mesh,
    PointLight,
    RenderSettings,
    Scene,
    SceneError,
    Sphere,
    Texture,
    Torus,
    TriangleMesh,
    render,
)


def scene_with(shape=None, light=None, camera=None):
    return Scene(camera or Camera(), [shape or Sphere("S")], [light or PointLight()])


def attempt(scene, settings=None):
    return render(scene, settings or RenderSettings(4, 4))


def square(**fields):
    v = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]], float)
    base = dict(vertices=v, triangles=np.array([[0, 1, 2], [0, 2, 3]]))
    base.update(fields)
    return Mesh("Quad", mesh=TriangleMesh(**base))


@pytest.mark.parametrize(
    "scene, message",
    [
        (scene_with(Torus("Ring", minor_radius=-0.1)),
         r"torus 'Ring': minor_radius: got -0.1; use a number > 0"),
        (scene_with(Torus("Ring", major_radius=0.0)), r"torus 'Ring': major_radius: got 0.0"),
        (scene_with(Torus("Ring", major_radius=float("inf"))),
         r"torus 'Ring': major_radius: .*finite"),
        (scene_with(Sphere("S", Material(name="Glass", inner_ior=0.0))),
         r"material 'Glass' \(on sphere 'S'\): inner_ior: got 0.0; use a number > 0"),
        (scene_with(Sphere("S", Material(name="Glass", outer_ior=-1.0))),
         r"material 'Glass'.*outer_ior: got -1.0"),
        (scene_with(Sphere("S", Material(name="M", reflectivity=1.5))),
         r"material 'M'.*reflectivity: got 1.5; use a number from 0.0 to 1.0"),
        (scene_with(Sphere("S", Material(name="M", transparency=float("nan")))),
         r"material 'M'.*transparency: got nan"),
        (scene_with(Sphere("S", Material(name="M", shininess=-3.0))),
         r"material 'M'.*shininess: got -3.0; use a number >= 0"),
        (scene_with(light=AreaLight(name="Panel", edge_u=(1, 0, 0), edge_v=(2, 0, 0))),
         r"area light 'Panel': edge_v: .*parallel"),
        (scene_with(light=AreaLight(name="Panel", centre=(0, float("inf"), 0))),
         r"area light 'Panel': centre: .*finite"),
        (scene_with(camera=Camera(aperture_radius=-1.0)),
         r"camera 'Camera': aperture_radius: got -1.0; use a number >= 0"),
        (scene_with(camera=Camera(focal_distance=0.0)), r"camera 'Camera': focal_distance"),
        (scene_with(camera=Camera(aperture_blades=2.5)),
         r"camera 'Camera': aperture_blades: got 2.5; use a whole number"),
        (scene_with(camera=Camera(aperture_blades=101)), r"camera 'Camera': aperture_blades"),
        (scene_with(camera=Camera(aperture_ratio=0.0)),
         r"camera 'Camera': aperture_ratio: got 0.0; use a number > 0"),
        (scene_with(camera=Camera(aperture_rotation=float("nan"))),
         r"camera 'Camera': aperture_rotation: got nan"),
        (scene_with(square(triangles=np.array([[0, 1, 2], [0, 2, 4]]))),
         r"mesh 'Quad': triangles: triangle 1 is \[0, 2, 4\]; vertex indices must lie in 0..3"),
        (scene_with(square(triangles=np.array([[0, 1, -1]]))), r"mesh 'Quad': triangles"),
        (scene_with(square(vertices=np.full((4, 3), np.nan))),
         r"mesh 'Quad': vertices: row 0 has NaN"),
        (scene_with(square(triangles=np.array([[0.0, 1.0, 2.0]]))),
         r"mesh 'Quad': triangles: got float64 numbers; use whole-number indices"),
        (scene_with(square(vertex_normals=np.zeros((3, 3)))),
         r"mesh 'Quad': vertex_normals: got shape \(3, 3\); use \(4, 3\)"),
        (scene_with(square(corner_uvs=np.zeros((2, 3, 2)) + np.inf)),
         r"mesh 'Quad': corner_uvs: contains NaN or infinity"),
    ],
)  # fmt: skip
def test_bad_feature_fields_are_named(scene, message):
    with pytest.raises(SceneError, match=message):
        attempt(scene)


@pytest.mark.parametrize(
    "field, value, message",
    [
        ("pixel_samples", 0, r"render settings: pixel_samples: got 0; use a whole number >= 1"),
        ("shadow_samples", -4, r"render settings: shadow_samples: got -4"),
        ("max_depth", -1, r"render settings: max_depth: got -1; use a whole number >= 0"),
        ("pixel_sampling", "poisson", r"pixel_sampling: got 'poisson'; use one of grid, jitt"),
        ("shadow_sampling", "sobol", r"shadow_sampling: got 'sobol'; use one of uniform, strat"),
        ("threads", -2, r"render settings: threads: got -2"),
        ("seed", 1.5, r"render settings: seed: got 1.5"),
    ],
)
def test_bad_settings_are_named(field, value, message):
    settings = RenderSettings(4, 4)
    setattr(settings, field, value)
    with pytest.raises(SceneError, match=message):
        attempt(scene_with(), settings)


def test_missing_and_unreadable_textures(tmp_path):
    material = Material(name="Wood", texture=Texture(tmp_path / "nowhere.png"))
    with pytest.raises(SceneError, match=r"material 'Wood' \(on sphere 'S'\): texture: .*"
                                         r"nowhere.png' does not exist"):  # fmt: skip
        attempt(scene_with(Sphere("S", material)))
    junk = tmp_path / "junk.png"
    junk.write_bytes(b"not an image at all")
    material.texture = Texture(junk)
    with pytest.raises(
        SceneError, match=r"material 'Wood'.*texture: .*junk.png' is not an image Pillow reads"
    ):
        attempt(scene_with(Sphere("S", material)))


def test_a_texture_replaces_the_diffuse_colour(tmp_path):
    """A one-colour image, sRGB-decoded, is what the sphere shows under ambient light."""
    from PIL import Image

    path = tmp_path / "orange.jpg"
    Image.new("RGB", (4, 2), (255, 128, 0)).save(path, quality=100)
    material = Material(diffuse=(0, 0, 1), texture=Texture(path))
    camera = Camera(eye=(0, -5, 0), view=(0, 1, 0), up=(0, 0, 1), fovy=30)
    scene = Scene(camera, [Sphere("S", material)], [], ambient=(1, 1, 1))
    centre = attempt(scene, RenderSettings(5, 5)).image[2, 2, :3]
    expected = [1.0, ((128 / 255 + 0.055) / 1.055) ** 2.4, 0.0]
    np.testing.assert_allclose(centre, expected, atol=0.01)


def test_lens_shift_moves_the_image_not_the_perspective():
    """A shift of (0.5, -0.25) half-widths/heights is the unshifted picture of a wider view
    cropped off-centre: the shifted 32x24 image is the block of an unshifted 64x48 image of
    twice the field that starts 24 pixels right and 15 down (verticals stay vertical)."""
    from core import Camera, Material, PointLight, RenderSettings, Scene, Sphere, render

    shapes = [Sphere("S", Material((0.8, 0.5, 0.2)), np.diag([1.0, 1.0, 1.0, 1.0]))]
    light = [PointLight((3, 4, 5), (20, 20, 20))]

    def picture(fovy_tan, shift, size):
        fovy = 2 * np.degrees(np.arctan(fovy_tan))
        camera = Camera((0, 0, 6.0), (0, 0, -1.0), (0, 1.0, 0), fovy, shift=shift)
        return render(Scene(camera, shapes, light), RenderSettings(*size)).image

    shifted = picture(0.2, (0.5, -0.25), (32, 24))
    wide = picture(0.4, (0.0, 0.0), (64, 48))
    np.testing.assert_allclose(shifted, wide[15:39, 24:56], atol=1e-5)
