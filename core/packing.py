"""Compile a `Scene` into `PackedScene`: the flat arrays that are all the kernels ever see.

The order is fixed: validate, then camera, materials (shapes refer to them by index), shapes,
lights. Every array has a fixed dtype and rank whatever the scene, so the kernels compile once
and load from the cache for every scene after.
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np

from core.kernels.shapes import SHAPE_SPHERE
from core.scene import RenderSettings, Scene, Sphere

SHAPE_KIND_OF_CLASS = {Sphere: SHAPE_SPHERE}


class PackedScene(NamedTuple):
    """Struct-of-arrays scene. Row i of every `shape_*` array describes shape i, and so on."""

    # rows: eye, forward (unit), right (scaled by the half-width of the image plane at
    # distance 1), up (scaled by its half-height)
    camera: np.ndarray  # float64 (4, 3)
    ambient: np.ndarray  # float64 (3,)
    background: np.ndarray  # float64 (3,)
    shape_kind: np.ndarray  # int32 (n,)
    shape_material: np.ndarray  # int32 (n,): row in material_*
    shape_object_from_world: np.ndarray  # float64 (n, 3, 4): affine rows, inverse transform
    material_diffuse: np.ndarray  # float64 (m, 3)
    material_specular: np.ndarray  # float64 (m, 3)
    material_shininess: np.ndarray  # float64 (m,)
    light_position: np.ndarray  # float64 (l, 3)
    light_intensity: np.ndarray  # float64 (l, 3)
    light_attenuation: np.ndarray  # float64 (l, 3): c0, c1, c2


def pack_scene(scene: Scene, settings: RenderSettings) -> PackedScene:
    """Validate `scene` and `settings`, then pack them. Raises `SceneError` on bad input."""
    scene.validate()
    settings.validate()

    materials, material_index = [], {}
    for shape in scene.shapes:
        if id(shape.material) not in material_index:
            material_index[id(shape.material)] = len(materials)
            materials.append(shape.material)

    n = len(scene.shapes)
    object_from_world = np.empty((n, 3, 4))
    for i, shape in enumerate(scene.shapes):
        object_from_world[i] = np.linalg.inv(np.asarray(shape.world_from_object, float))[:3]

    return PackedScene(
        camera=_pack_camera(scene, settings),
        ambient=np.asarray(scene.ambient, float),
        background=np.asarray(scene.background, float),
        shape_kind=np.array([SHAPE_KIND_OF_CLASS[type(s)] for s in scene.shapes], np.int32),
        shape_material=np.array([material_index[id(s.material)] for s in scene.shapes], np.int32),
        shape_object_from_world=object_from_world,
        material_diffuse=np.array([m.diffuse for m in materials], float).reshape(-1, 3),
        material_specular=np.array([m.specular for m in materials], float).reshape(-1, 3),
        material_shininess=np.array([m.shininess for m in materials], float),
        light_position=np.array([lt.position for lt in scene.lights], float).reshape(-1, 3),
        light_intensity=np.array([lt.intensity for lt in scene.lights], float).reshape(-1, 3),
        light_attenuation=np.array([lt.attenuation for lt in scene.lights], float).reshape(-1, 3),
    )


def _pack_camera(scene: Scene, settings: RenderSettings) -> np.ndarray:
    cam = scene.camera
    forward = np.asarray(cam.view, float)
    forward /= np.linalg.norm(forward)
    right = np.cross(forward, np.asarray(cam.up, float))
    right /= np.linalg.norm(right)
    up = np.cross(right, forward)
    half_height = math.tan(math.radians(cam.fovy) / 2.0)
    half_width = half_height * settings.width / settings.height
    return np.array([cam.eye, forward, right * half_width, up * half_height], float)
