"""Light Path's outputs (core.kernels.shader_program.path_ray_at) against what each ray is,
known here by construction: a probe square glowing with three outputs as its colour, seen
by an orthographic camera directly, in a 45-degree mirror, through a glass slab of index 1
(it neither bends nor reflects) and through a Transparent sheet. Cycles' rules: each
bounce sets the ray's flags anew, a transparent surface keeps them (a camera ray passing
one is still a camera ray), and Ray Length is the distance from the ray's last surface."""

import numpy as np
import pytest

from core import (
    Box,
    Environment,
    Link,
    Material,
    Mesh,
    RenderSettings,
    Scene,
    ShaderNode,
    TriangleMesh,
    render,
)
from tests.core.test_environment import hits, look_at_ball

SIZE = 8
PATH = ShaderNode("light_path")


def _probe(corners, outputs, scale=(1.0, 1.0, 1.0)):
    """A square glowing with Light Path's `outputs` (three names) times `scale`, as RGB."""
    channels = {}
    for axis, name, factor in zip("XYZ", outputs, scale, strict=True):
        scaled = ShaderNode("math", {"A": Link(PATH, name), "B": factor},
                            settings={"operation": "MULTIPLY"})  # fmt: skip
        channels[axis] = Link(scaled, "Value")
    colour = Link(ShaderNode("combine", channels), "Vector")
    glow = Material(surface=ShaderNode("emission", {"Color": colour, "Strength": 1.0}))
    mesh = TriangleMesh(np.asarray(corners, float), np.array([(0, 1, 2), (0, 2, 3)]))
    return Mesh("Probe", glow, np.eye(4), mesh=mesh)


def _facing_camera(y):
    """A square x, z in -5..5 at depth y (the camera looks along +Y from y = -10)."""
    return [(-5, y, -5), (5, y, -5), (5, y, 5), (-5, y, 5)]


def _seen(shapes):
    scene = Scene(look_at_ball(), shapes)
    settings = RenderSettings(SIZE, SIZE, pixel_samples=1, max_depth=4)
    return render(scene, settings).image[..., :3].astype(float)


def _uniform(seen, rgb):
    np.testing.assert_allclose(seen.reshape(-1, 3), np.tile(rgb, (SIZE * SIZE, 1)), atol=1e-6)


def test_a_camera_ray_is_one_and_its_length_is_the_distance_from_the_camera():
    probe = _probe(_facing_camera(2.0), ("Is Camera Ray", "Is Reflection Ray", "Ray Length"),
                   (1.0, 1.0, 0.05))  # fmt: skip
    _uniform(_seen([probe]), (1.0, 0.0, 12.0 * 0.05))


def test_a_camera_ray_starts_at_the_clip_start():
    """Camera › Clip Start 2: the probe is 10 away, and a square 1 in front of the camera is
    not seen (Cycles clips so)."""
    camera = look_at_ball()
    camera.clip_start = 2.0
    probe = _probe(_facing_camera(2.0), ("Is Camera Ray", "Ray Length", "Ray Depth"),
                   (1.0, 0.05, 1.0))  # fmt: skip
    near = Mesh("Near", Material(diffuse=(1.0, 0.0, 0.0)), np.eye(4),
                mesh=TriangleMesh(np.asarray(_facing_camera(-9.0), float),
                                  np.array([(0, 1, 2), (0, 2, 3)])))  # fmt: skip
    scene = Scene(camera, [near, probe])
    seen = render(scene, RenderSettings(SIZE, SIZE, pixel_samples=1)).image[..., :3]
    _uniform(seen.astype(float), (1.0, 0.5, 0.0))


def test_a_mirrored_ray_is_a_glossy_reflection_ray_one_bounce_deep():
    """The mirror in the plane y = x turns the camera's +Y rays to +X, to the probe at x = 4:
    a ray meeting the mirror at x travels 4 - x to it."""
    mirror = Mesh("Mirror", Material(diffuse=(0.0, 0.0, 0.0), reflectivity=1.0), np.eye(4),
                  mesh=TriangleMesh(np.array([(-3, -3, -3), (3, 3, -3), (3, 3, 3), (-3, -3, 3)],
                                             float), np.array([(0, 1, 2), (0, 2, 3)])))  # fmt: skip
    wall = [(4, -5, -5), (4, 5, -5), (4, 5, 5), (4, -5, 5)]
    outputs = ("Is Reflection Ray", "Is Glossy Ray", "Ray Length")
    seen = _seen([mirror, _probe(wall, outputs, (1.0, 1.0, 0.1))])
    points, _ = hits(SIZE)
    expected = np.stack([np.ones(SIZE * SIZE), np.ones(SIZE * SIZE),
                         (4.0 - points[..., 0].ravel()) * 0.1], axis=-1)  # fmt: skip
    np.testing.assert_allclose(seen.reshape(-1, 3), expected, atol=1e-6)
    depths = _seen([mirror, _probe(wall, ("Ray Depth", "Glossy Depth", "Is Camera Ray"))])
    _uniform(depths, (1.0, 1.0, 0.0))


def test_a_ray_through_glass_is_a_transmission_ray_two_refractions_deep():
    """A slab y in -1..1 of index 1: in and out, then 2 to the probe at y = 3."""
    slab = np.diag([6.0, 1.0, 6.0, 1.0])
    glass = Box("Slab", Material(diffuse=(0.0, 0.0, 0.0), transparency=1.0, inner_ior=1.0), slab)
    probe = _probe(_facing_camera(3.0), ("Is Transmission Ray", "Transmission Depth",
                                         "Ray Length"), (1.0, 0.5, 0.25))  # fmt: skip
    _uniform(_seen([glass, probe]), (1.0, 1.0, 0.5))
    depths = _probe(_facing_camera(3.0), ("Ray Depth", "Glossy Depth", "Is Reflection Ray"))
    _uniform(_seen([glass, depths]), (2.0, 0.0, 0.0))


def test_a_camera_ray_through_a_transparent_sheet_is_still_a_camera_ray():
    sheet = Mesh("Veil", Material(diffuse=(0.0, 0.0, 0.0), transparent=(1.0, 1.0, 1.0)),
                 np.eye(4), mesh=TriangleMesh(np.asarray(_facing_camera(0.0), float),
                                              np.array([(0, 1, 2), (0, 2, 3)])))  # fmt: skip
    probe = _probe(_facing_camera(3.0), ("Is Camera Ray", "Transparent Depth", "Ray Length"),
                   (1.0, 1.0, 0.25))  # fmt: skip
    _uniform(_seen([sheet, probe]), (1.0, 1.0, 0.75))
    never = _probe(_facing_camera(3.0), ("Is Diffuse Ray", "Diffuse Depth", "Ray Depth"))
    _uniform(_seen([sheet, never]), (0.0, 0.0, 0.0))


@pytest.mark.parametrize("projection", ["orthographic", "perspective"])
def test_a_camera_ray_ends_at_the_clip_end_plane_and_sees_the_world_beyond(projection):
    """Camera › Clip End: a red square 12 along the view, before a green World. At Clip End
    11 it is gone, the World shown in its place; at 12.5 it is seen whole, even at the
    corners of a 60 degree view, 15.4 away along their rays (the limit is a plane across the
    view axis, as Cycles' is, not a sphere)."""
    square = Mesh("Square", Material(diffuse=(0.0, 0.0, 0.0), emission=(1.0, 0.0, 0.0)),
                  np.eye(4), mesh=TriangleMesh(np.asarray(_facing_camera(2.0), float) * 1.6,
                                               np.array([(0, 1, 2), (0, 2, 3)])))  # fmt: skip
    square.world_from_object[1, 3] = 2.0 - 1.6 * 2.0  # x, z in -8..8, still at depth y = 2
    for clip_end, expected in ((11.0, (0.0, 1.0, 0.0)), (12.5, (1.0, 0.0, 0.0))):
        camera = look_at_ball()
        camera.projection, camera.fovy, camera.clip_end = projection, 60.0, clip_end
        scene = Scene(camera, [square], environment=Environment(colour=(0.0, 1.0, 0.0)))
        seen = render(scene, RenderSettings(SIZE, SIZE, pixel_samples=1)).image[..., :3]
        _uniform(seen.astype(float), expected)
