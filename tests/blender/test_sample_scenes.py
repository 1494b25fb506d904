"""Every sample scene renders headless, small, with its feature visibly present: each test
asserts something that would fail without the feature (run in Blender 5.0 here, and inside
Blender 3.4 by test_blender34_cli, so every file opens in both)."""

import math

import numpy as np
import pytest
from PIL import Image

from core.textures import srgb_to_linear
from tests.blender.conftest import ROOT

pytestmark = pytest.mark.bpy
SAMPLES = ROOT / "sample_blends"


def open_sample(bpy, name, scene_name=None):
    bpy.ops.wm.open_mainfile(filepath=str(SAMPLES / name))
    return bpy.data.scenes[scene_name] if scene_name else bpy.context.scene


def render(bpy, scene, path, size=None):
    """Linear RGB (height, width, 3) of `scene` rendered at `size` (width, height)."""
    if size is not None:
        scene.render.resolution_x, scene.render.resolution_y = size
    scene.render.resolution_percentage = 100
    scene.render.filepath = str(path)
    bpy.ops.render.render(write_still=True, scene=scene.name)
    return srgb_to_linear(np.asarray(Image.open(path), dtype=float)[..., :3] / 255.0)


def pixel_of(scene, point):
    """(column, row from the top) where world `point` shows in the image, for the samples'
    unparented cameras with a vertical field of view. Worked out from the camera's own
    location and rotation: a camera only in a scene other than the file's active one has
    no up-to-date matrix_world."""
    from mathutils import Matrix, Vector

    camera = scene.camera
    pose = Matrix.LocRotScale(camera.location, camera.rotation_euler, Vector((1, 1, 1)))
    x, y, z = pose.inverted() @ Vector(point)
    assert camera.data.sensor_fit == "VERTICAL"
    width, height = scene.render.resolution_x, scene.render.resolution_y
    tan_half = math.tan(camera.data.angle_y / 2.0)
    ndc_x = x / -z / (tan_half * width / height)
    ndc_y = y / -z / tan_half
    return int((ndc_x + 1.0) / 2.0 * width), int((1.0 - ndc_y) / 2.0 * height)


def camera_right(scene):
    from mathutils import Vector

    return scene.camera.rotation_euler.to_matrix() @ Vector((1.0, 0.0, 0.0))


def hue_match(rgb, reference):
    """Cosine between colours: 1 when one is a brighter or darker copy of the other."""
    rgb, reference = np.asarray(rgb, float), np.asarray(reference, float)
    return float(rgb @ reference / (np.linalg.norm(rgb) * np.linalg.norm(reference) + 1e-12))


def world_point(obj, local):
    from mathutils import Vector

    return tuple(obj.matrix_world @ Vector(local))


def visible_point(obj):
    """A point on the object the camera sees: a torus's tube, a cube's top face (the torus
    stands in front of its middle), the upper half of a sphere or cylinder (the cone's tip
    and the monkey are in front of their middles), else its origin."""
    if obj.whitted.shape == "TORUS":
        return world_point(obj, (0.0, -obj.whitted.major_radius, 0.0))
    if obj.whitted.shape == "CUBE":
        return world_point(obj, (0.0, 0.0, 1.0))
    if obj.whitted.shape in {"SPHERE", "CYLINDER"}:
        return world_point(obj, (0.0, -0.3, 0.6))
    return tuple(obj.matrix_world.translation)


def test_primitives_each_shape_shows_its_own_colour(bpy_with_whitted, tmp_path):
    bpy = bpy_with_whitted
    scene = open_sample(bpy, "primitives.blend")
    for material in bpy.data.materials:
        material.whitted.specular = (0.0, 0.0, 0.0)  # no white highlight on the probe pixel
    image = render(bpy, scene, tmp_path / "primitives.png", (240, 160))
    names = ["Sphere", "Cube", "Cylinder", "Cone", "Torus", "Mesh"]
    assert {bpy.data.objects[n].whitted.shape for n in names[:5]} == {
        "SPHERE", "CUBE", "CYLINDER", "CONE", "TORUS"
    }  # fmt: skip
    for name in names:
        obj = bpy.data.objects[name]
        x, y = pixel_of(scene, visible_point(obj))
        diffuse = obj.material_slots[0].material.diffuse_color[:3]
        assert hue_match(image[y, x], diffuse) > 0.99, (name, image[y, x], diffuse)


def local_spread(image, x, y, radius=3):
    """Summed standard deviation of the channels in a square window around (x, y)."""
    window = image[y - radius : y + radius + 1, x - radius : x + radius + 1]
    return float(window.reshape(-1, 3).std(axis=0).sum())


def test_texture_mapping_every_primitive_shows_texture_cells(bpy_with_whitted, tmp_path):
    bpy = bpy_with_whitted
    scene = open_sample(bpy, "texture_mapping.blend")
    probes = {name: visible_point(bpy.data.objects[name])
              for name in ["Sphere", "Cube", "Cylinder", "Cone", "Torus", "Mesh"]}  # fmt: skip
    grid = bpy.data.materials["UV Grid"]
    grid.whitted.specular = (0.0, 0.0, 0.0)  # a highlight would vary fast on its own
    textured = render(bpy, scene, tmp_path / "textured.png", (360, 240))
    grid.whitted.image = None
    plain = render(bpy, scene, tmp_path / "plain.png", (360, 240))
    # Without highlights a texture multiplies the diffuse shading: textured / plain is the
    # texture over the plain colour, and shows several texture cells around each probe
    texture = textured / np.maximum(plain, 1e-4)
    for name, point in probes.items():
        x, y = pixel_of(scene, point)
        assert local_spread(texture, x, y) > 0.15, name  # untextured: 1 everywhere


def mixed_pixels(image, colour, background, margin=0.25):
    """Pixels whose channel ratio lies strictly between the object's and the background's:
    a matte object's pixels keep its ratio at any brightness, so only a pixel that averages
    object and sky can fall in between."""
    dominant, other = int(np.argmax(colour)), int(np.argsort(colour)[0])
    ratio = image[..., other] / np.maximum(image[..., dominant], 1e-6)
    low = colour[other] / colour[dominant]
    high = background[other] / background[dominant]
    lo, hi = low + margin * (high - low), high - margin * (high - low)
    return int(np.count_nonzero((ratio > lo) & (ratio < hi)))


def test_supersampling_adds_intermediate_edge_pixels(bpy_with_whitted, tmp_path):
    bpy = bpy_with_whitted
    open_sample(bpy, "supersampling.blend")
    off, on = bpy.data.scenes["Supersampling Off"], bpy.data.scenes["Supersampling On"]
    assert (off.whitted.pixel_samples, on.whitted.pixel_samples) == (1, 3)
    background = np.array(off.world.color)
    images = {
        s.name: render(bpy, s, tmp_path / f"{s.whitted.pixel_samples}.png") for s in (off, on)
    }
    for material in ("Blue", "Red"):
        colour = np.array(bpy.data.materials[material].diffuse_color[:3])
        edge_off = mixed_pixels(images[off.name], colour, background)
        edge_on = mixed_pixels(images[on.name], colour, background)
        assert edge_off == 0, material
        assert edge_on > 30, material  # a good part of the outline's pixels


def disc_mask(scene, obj, shape, grow=0.9):
    """Pixels inside the projected outline of a sphere object (radius from its scale)."""
    right = camera_right(scene)
    centre = obj.matrix_world.translation
    cx, cy = pixel_of(scene, centre)
    ex, _ = pixel_of(scene, centre + right * obj.scale[0])
    radius = abs(ex - cx)
    y, x = np.mgrid[0 : shape[0], 0 : shape[1]]
    return (x - cx) ** 2 + (y - cy) ** 2 < (grow * radius) ** 2


def test_mirror_balls_reflect_the_red_ball(bpy_with_whitted, tmp_path):
    bpy = bpy_with_whitted
    scene = open_sample(bpy, "mirror.blend")
    size = (200, 150)
    mirrors = [bpy.data.objects[n] for n in ("Mirror Ball Left", "Mirror Ball Right")]

    def red_in_mirrors(image):
        inside = np.zeros(image.shape[:2], bool)
        for obj in mirrors:
            inside |= disc_mask(scene, obj, image.shape)
        # Not the red ball itself, which stands in front of the right mirror ball
        inside &= ~disc_mask(scene, bpy.data.objects["Red Ball"], image.shape, grow=1.4)
        r, g, b = image[inside].T
        return int(np.count_nonzero((r > 0.05) & (r > 3 * g) & (r > 3 * b)))

    scene.render.resolution_x, scene.render.resolution_y = size
    reflecting = red_in_mirrors(render(bpy, scene, tmp_path / "mirror.png"))
    bpy.data.materials["Mirror"].whitted.reflectivity = 0.0
    matte = red_in_mirrors(render(bpy, scene, tmp_path / "matte.png"))
    assert matte == 0
    assert reflecting > 20


def test_refraction_glass_ball_shows_the_wall_upside_down_and_swapped(bpy_with_whitted, tmp_path):
    """A ball lens of index 1.53 (focal length 1.44 radii from its centre) forms an inverted
    image of a wall 4.5 radii behind it: left of the centre shows the blue right half."""
    bpy = bpy_with_whitted
    scene = open_sample(bpy, "refraction.blend")
    glass = bpy.data.materials["Glass"].whitted
    assert (glass.outer_ior, round(glass.inner_ior, 6)) == (1.0, 1.53)
    image = render(bpy, scene, tmp_path / "glass.png", (200, 150))
    ball = bpy.data.objects["Glass Ball"]
    offset = 0.45 * ball.scale[0]
    for side, swapped in ((-offset, (2, 0)), (offset, (0, 2))):
        point = world_point(ball, (0.0, 0.0, 0.0))
        x, y = pixel_of(scene, (point[0] + side, point[1], point[2]))
        wall_x, wall_y = pixel_of(scene, (point[0] + side, 5.0, point[2]))
        strong, weak = swapped
        assert image[y, x, strong] > 2.0 * image[y, x, weak], (side, image[y, x])
        # Beside the ball, the wall itself: the other colour on that side
        behind = image[wall_y, x + (-40 if side < 0 else 40)]
        assert behind[weak] > 2.0 * behind[strong], (side, behind)


def test_csg_the_three_report_solids(bpy_with_whitted, tmp_path):
    bpy = bpy_with_whitted
    scene = open_sample(bpy, "csg.blend")
    for material in bpy.data.materials:
        material.whitted.specular = (0.0, 0.0, 0.0)
    size = (480, 220)
    image = render(bpy, scene, tmp_path / "csg.png", size)
    objects = bpy.data.objects

    def colour_at(point):
        x, y = pixel_of(scene, point)
        return image[y, x]

    steel = bpy.data.materials["Steel Blue"].diffuse_color[:3]
    amber = bpy.data.materials["Amber"].diffuse_color[:3]
    green = bpy.data.materials["Green"].diffuse_color[:3]
    # Sphere ∩ cube: its outline lies inside both the cube's and the sphere's (checked
    # below against renders of each alone), and is smaller than either
    rounded = objects["Sphere And Cube"]
    assert hue_match(colour_at(world_point(rounded, (0.0, -1.0, 0.0))), steel) > 0.99
    left_third = (slice(None), slice(0, size[0] // 3))

    def steel_pixels(picture):
        region = picture[left_third]
        cosine = (
            region
            @ np.asarray(steel)
            / (np.linalg.norm(region, axis=-1) * np.linalg.norm(steel) + 1e-12)
        )
        return cosine > 0.99

    intersection = steel_pixels(image)
    # The union: each cylinder's far end is there
    jack = objects["Three Cylinders"]
    arms = [jack, objects["Cylinder Arm 1"], objects["Cylinder Arm 2"]]
    for arm in arms:
        end = world_point(arm, (0.0, 0.0, 0.9))
        if pixel_of(scene, end)[1] < 0:
            end = world_point(arm, (0.0, 0.0, -0.9))
        assert hue_match(colour_at(end), amber) > 0.99, arm.name
    # Cube − cylinder: the face is there; the line of sight through the cube's centre runs
    # inside the bore from face to face (it is 0.55 wide, the view 18° off its axis), so it
    # shows what lies behind
    block = objects["Bored Cube"]
    assert hue_match(colour_at(world_point(block, (0.8, -1.0, 0.8))), green) > 0.99
    assert hue_match(colour_at(world_point(block, (0.0, 0.0, 0.0))), green) < 0.97
    # Without the Boolean modifiers: the plain cube fills the bore, and is bigger
    for obj in (rounded, block):
        for modifier in obj.modifiers:
            modifier.show_render = False
    image = render(bpy, scene, tmp_path / "plain.png", size)
    assert hue_match(colour_at(world_point(block, (0.0, 0.0, 0.0))), green) > 0.99
    cube_alone = steel_pixels(image)
    rounded.hide_render, objects["Rounding Sphere"].hide_render = True, False
    sphere_alone = steel_pixels(render(bpy, scene, tmp_path / "sphere.png", size))
    assert np.count_nonzero(intersection & ~(cube_alone & sphere_alone)) < 10  # edge pixels
    smaller = min(np.count_nonzero(cube_alone), np.count_nonzero(sphere_alone))
    assert np.count_nonzero(intersection) < 0.95 * smaller


def torus_visibility(xs, y, light_half, light_height, torus_z, major, minor, grid=48):
    """Fraction of a square light (centred above the origin, edges along x and y) seen from
    floor points (x, y, 0): dense sampling of the light, and of each segment through the
    torus's slab, in numpy, independent of the renderer."""
    a = (np.arange(grid) + 0.5) / grid * 2.0 - 1.0
    lx, ly = np.meshgrid(a * light_half, a * light_half)
    lx, ly = lx.ravel(), ly.ravel()
    z = np.linspace(torus_z - minor, torus_z + minor, 201)
    s = z / light_height  # where along each segment the slab is
    seen = []
    for x in xs:
        px = x + (lx[:, None] - x) * s
        py = y + (ly[:, None] - y) * s
        tube = (np.hypot(px, py) - major) ** 2 + (z - torus_z) ** 2
        seen.append(1.0 - np.mean(np.any(tube < minor * minor, axis=1)))
    return np.array(seen)


def test_soft_shadow_penumbra_has_the_width_geometry_predicts(bpy_with_whitted, tmp_path):
    bpy = bpy_with_whitted
    open_sample(bpy, "soft_shadow.blend")
    torus = bpy.data.objects["Torus"]
    major, minor = torus.whitted.major_radius, torus.whitted.minor_radius
    height = torus.location.z
    size, camera_height, half_view = 160, 1000.0, 140.0
    profiles = {}
    for scene_name in ("Soft Shadow", "Hard Shadow"):
        scene = bpy.data.scenes[scene_name]
        light = next(o for o in scene.objects if o.type == "LIGHT")
        # Straight down from above the light: image x is world x, linearly
        data = bpy.data.cameras.new("Top")
        data.sensor_fit = "VERTICAL"
        data.angle_y = 2.0 * math.atan(half_view / camera_height)
        data.clip_end = 2.0 * camera_height  # (a new camera's 100 would end its rays midway)
        top = bpy.data.objects.new("Top", data)
        top.location = (0.0, 0.0, camera_height)
        scene.collection.objects.link(top)
        scene.camera = top
        scene.world.whitted.ambient = (0.0, 0.0, 0.0)  # the light's shadow alone
        row = size // 2
        lit = render(bpy, scene, tmp_path / f"{scene_name}.png", (size, size))[row, :, 1]
        torus.hide_render = True
        bare = render(bpy, scene, tmp_path / f"{scene_name} bare.png", (size, size))[row, :, 1]
        torus.hide_render = False
        profiles[scene_name] = (lit / bare, light)
    pixel = 2.0 * half_view / size
    xs = (np.arange(size) + 0.5) * pixel - half_view
    y = (size / 2 - (row + 0.5)) * pixel
    # The floor beside the torus where the camera sees past the torus's rim
    rim = (major + minor) * camera_height / (camera_height - height - minor)
    right = xs > rim + 2.0 * pixel
    visibility, light = profiles["Soft Shadow"]
    assert light.data.size == 50.0
    expected = torus_visibility(xs[right], y, 25.0, light.location.z, height, major, minor)
    np.testing.assert_allclose(visibility[right], expected, atol=0.08)

    def penumbra_width(profile):
        inside = (profile > 0.1) & (profile < 0.9)
        return np.count_nonzero(inside) * pixel

    predicted = penumbra_width(expected)
    assert predicted > 8.0  # several pixels wide: a real test of the width
    assert penumbra_width(visibility[right]) == pytest.approx(predicted, rel=0.25)
    hard, _ = profiles["Hard Shadow"]
    assert penumbra_width(hard[right]) <= pixel  # a point light's shadow edge: one pixel


def sharpness(image, mask):
    """Local contrast: the mean absolute Laplacian of the luminance inside mask (a blur
    lowers it more than it lowers the gradient)."""
    luminance = image @ np.array([0.2126, 0.7152, 0.0722])
    laplacian = np.zeros_like(luminance)
    laplacian[1:-1, 1:-1] = (
        luminance[:-2, 1:-1] + luminance[2:, 1:-1] + luminance[1:-1, :-2] + luminance[1:-1, 2:]
        - 4.0 * luminance[1:-1, 1:-1]
    )  # fmt: skip
    return float(np.abs(laplacian)[mask].mean())


def test_depth_of_field_is_sharp_only_at_the_focus(bpy_with_whitted, tmp_path):
    bpy = bpy_with_whitted
    open_sample(bpy, "depth_of_field.blend")
    names = ["Front", "Middle", "Back"]
    spheres = [bpy.data.objects[f"{n} Sphere"] for n in names]
    contrast = np.zeros((3, 3))  # [focused scene, sphere]
    for i, name in enumerate(names):
        scene = bpy.data.scenes[f"Focus {name}"]
        assert scene.camera.data.dof.focus_object == spheres[i]
        image = render(bpy, scene, tmp_path / f"{name}.png", (200, 125))
        for j, sphere in enumerate(spheres):
            contrast[i, j] = sharpness(image, disc_mask(scene, sphere, image.shape))
    for j in range(3):
        others = [contrast[i, j] for i in range(3) if i != j]
        assert contrast[j, j] > 1.3 * max(others), (names[j], contrast)


def test_teapot_flat_shading_shows_facets_smooth_does_not(bpy_with_whitted, tmp_path):
    bpy = bpy_with_whitted
    scene = open_sample(bpy, "teapot.blend")
    flat, smooth = bpy.data.objects["Teapot Flat"], bpy.data.objects["Teapot Smooth"]
    assert 5500 < len(smooth.data.polygons) < 7000
    assert not any(p.use_smooth for p in flat.data.polygons)
    assert all(p.use_smooth for p in smooth.data.polygons)
    image = render(bpy, scene, tmp_path / "teapots.png", (400, 200))
    luminance = image @ np.array([0.2126, 0.7152, 0.0722])
    # Second differences: a facet edge is a kink in brightness, smooth shading has none
    kinks = np.abs(luminance[1:-1, :-2] - 2 * luminance[1:-1, 1:-1] + luminance[1:-1, 2:])
    kinks += np.abs(luminance[:-2, 1:-1] - 2 * luminance[1:-1, 1:-1] + luminance[2:, 1:-1])
    body = {}
    for obj in (flat, smooth):
        x, y = pixel_of(scene, world_point(obj, (0.0, 0.0, 1.1)))
        body[obj.name] = float(kinks[y - 12 : y + 8, x - 25 : x + 25].mean())
    assert body["Teapot Flat"] > 2.0 * body["Teapot Smooth"], body


def test_final_scene_has_the_report_settings_and_renders(bpy_with_whitted, tmp_path):
    import sys

    bpy = bpy_with_whitted
    scene = open_sample(bpy, "final_scene.blend")
    settings = scene.whitted
    assert (scene.render.resolution_x, scene.render.resolution_y) == (500, 500)
    assert (settings.pixel_samples, settings.pixel_sampling) == (3, "GRID")
    assert (settings.shadow_samples, settings.max_depth) == (40, 50)
    export = sys.modules["whitted.export"]
    exported, _, warnings = export.convert(bpy.context.evaluated_depsgraph_get())
    assert warnings == []
    kinds = sorted(type(s).__name__ for s in exported.shapes)
    assert kinds.count("Csg") == 3  # table, mug, bowl
    assert kinds.count("Torus") == 2 and kinds.count("Cone") == 1
    (light,) = exported.lights
    assert np.linalg.norm(light.edge_u) == pytest.approx(50.0)
    assert np.linalg.norm(light.edge_v) == pytest.approx(50.0)
    teapot = next(s for s in exported.shapes if s.name == "Teapot")
    assert 5500 < len(teapot.mesh.triangles) < 7000
    # Small and quick: the mirror wall shows the room (it differs from a matte wall)
    settings.shadow_samples, settings.pixel_samples = 4, 1
    mirrored = render(bpy, scene, tmp_path / "final.png", (64, 64))
    bpy.data.materials["Mirror"].whitted.reflectivity = 0.0
    matte = render(bpy, scene, tmp_path / "matte.png", (64, 64))
    wall = (slice(2, 14), slice(8, 56))
    assert np.all(np.isfinite(mirrored))
    assert np.abs(mirrored[wall] - matte[wall]).mean() > 0.05


@pytest.mark.parametrize("name", sorted(p.name for p in SAMPLES.glob("*.blend")))
def test_each_sample_opens_framed_through_its_camera(bpy_with_whitted, name):
    """Opened as a user opens it (with its UI), every 3D view looks through the scene's
    camera, and the view's and the camera's clip distances hold the whole scene (Blender's
    defaults, 1 km, cut the final scene and put the view inside an object)."""
    bpy = bpy_with_whitted
    from mathutils import Vector  # Blender's, once bpy is loaded

    bpy.ops.wm.open_mainfile(filepath=str(SAMPLES / name), load_ui=True)
    scene = bpy.context.scene
    corners = np.array(
        [
            obj.matrix_world @ Vector(corner)
            for obj in scene.objects
            if obj.type == "MESH"
            for corner in obj.bound_box
        ]  # fmt: skip
    )
    size = float(np.linalg.norm(corners.max(axis=0) - corners.min(axis=0)))
    views = [area.spaces.active for screen in bpy.data.screens for area in screen.areas
             if area.type == "VIEW_3D"]  # fmt: skip
    assert views
    for view in views:
        assert view.region_3d.view_perspective == "CAMERA"
        assert view.clip_end >= size and view.clip_start <= 0.01 * size
    eye = np.array(scene.camera.matrix_world.translation)
    farthest = float(np.linalg.norm(corners - eye, axis=1).max())
    assert scene.camera.data.clip_end > farthest
    # the report's scenes keep the report's pictures: its glass rule, no photon pass (their
    # CS488 lights would send photons under Blender's defaults)
    for each in bpy.data.scenes:
        settings = each.whitted
        assert settings.glass_shadows == "ATTENUATED", each.name
        assert not (settings.use_caustics_reflective or settings.use_caustics_refractive)
