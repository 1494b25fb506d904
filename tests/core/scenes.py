"""Small scenes built twice: as core objects and as the reference tracer's dicts."""

import numpy as np

from core import Camera, Material, PointLight, Scene, Sphere
from tests.reference_tracer import sphere_quadric


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
