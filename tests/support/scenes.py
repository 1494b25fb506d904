"""Small scenes built twice: as core objects and as the reference tracer's dicts."""

import numpy as np

from core import (
    AreaLight,
    Box,
    Camera,
    Csg,
    Cylinder,
    Material,
    Mesh,
    PointLight,
    Scene,
    Sphere,
    Texture,
    Torus,
    TriangleMesh,
)
from tests.support.meshes import icosphere
from tests.support.reference_tracer import sphere_quadric


def translate_scale(centre, radius):
    m = np.diag([radius, radius, radius, 1.0])
    m[:3, 3] = centre
    return m


def ball_on_ground(light_position=(0.0, 0.0, 10.0)):
    """A unit ball 1.5 above a ground sphere whose top (z=0) is nearly flat; one light."""
    ball = Material(diffuse=(0.8, 0.2, 0.1), specular=(0.6, 0.6, 0.6), shininess=20.0, name="ball")
    ground = Material(diffuse=(0.5, 0.5, 0.5), name="ground")
    shapes = [
        Sphere("Ball", ball, translate_scale((0.0, 0.0, 2.5), 1.0)),
        Sphere("Ground", ground, translate_scale((0.0, 0.0, -1e4), 1e4)),
    ]
    light = PointLight(light_position, (120.0, 120.0, 120.0), (1.0, 0.0, 1.0), name="Key")
    camera = Camera(eye=(0.0, -14.0, 7.0), view=(0.0, 14.0, -5.0), up=(0.0, 0.0, 1.0), fovy=45.0)
    return Scene(camera, shapes, [light], ambient=(0.1, 0.1, 0.1), background=(0.2, 0.3, 0.4))


def reference_of(scene: Scene):
    """The reference tracer's description of a core scene of spheres."""
    spheres = [
        {
            "Q": sphere_quadric(s.world_from_object),
            "kd": s.material.diffuse,
            "ks": s.material.specular,
            "p": s.material.shininess,
        }
        for s in scene.shapes
    ]
    lights = [
        {"position": lt.position, "intensity": lt.intensity, "attenuation": lt.attenuation}
        for lt in scene.lights
    ]
    return spheres, lights


GROUND_KD = (0.6, 0.5, 0.4)


def ground(material=None):
    """A 200 x 200 slab whose top face is the plane z = 0."""
    m = np.diag([100.0, 100.0, 1.0, 1.0])
    m[2, 3] = -1.0
    return Box("Ground", material or Material(diffuse=GROUND_KD), m)


def look_down(eye=(0.0, -3.0, 8.0)):
    return Camera(eye=eye, view=(0.0, 3.0, -8.0), up=(0.0, 0.0, 1.0), fovy=60.0)


LIGHT = PointLight((0.0, -4.0, 4.0), (1.0, 1.0, 1.0))
AREA = AreaLight((0.0, 0.0, 4.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (5.0, 5.0, 5.0))


def moved(x):
    m = np.eye(4)
    m[0, 3] = x
    return m


def one_of_each_kind():
    """Small scenes, each with what packs into a different table (no shapes, one mesh, only
    CSG, only an area light, a texture, all of them), by name."""
    vertices, triangles = icosphere(1)
    mesh = Mesh("Ball", mesh=TriangleMesh(vertices, triangles))
    checker = np.zeros((2, 2, 3))
    checker[0, 0] = checker[1, 1] = 1.0
    textured = Material(texture=Texture(pixels=checker))
    csg = Csg("Cut", operation="difference", left=Box("B"), right=Cylinder("C"))
    return {
        "empty": Scene(),
        "one sphere": Scene(shapes=[Sphere("S")], lights=[LIGHT]),
        "one mesh": Scene(shapes=[mesh], lights=[LIGHT]),
        "only CSG": Scene(shapes=[csg], lights=[LIGHT]),
        "only an area light": Scene(lights=[AREA]),
        "textured": Scene(shapes=[Sphere("S", textured)], lights=[LIGHT]),
        "many shapes": Scene(
            camera=Camera(eye=(0, -8, 0), view=(0, 1, 0), up=(0, 0, 1), fovy=40),
            shapes=[
                Sphere("S", world_from_object=moved(-2)),
                Torus("T", world_from_object=moved(2)),
                mesh,
                csg,
                Sphere("S2", textured, world_from_object=moved(4)),
            ],
            lights=[LIGHT, AREA],
        ),
    }
