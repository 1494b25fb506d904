"""Expected pixels of a Whitted-tagged .blend, computed without the add-on's exporter.

The scene is read from Blender data here, the field of view from the lens formula (not from
Blender's projection matrix as the exporter does), and shaded by the plain-Python reference
tracer. Only the documented power mapping, intensity = colour * power / (4 pi^2), is shared.
"""

import math

import numpy as np

from tests.support.reference_tracer import (
    camera_ray,
    orthographic_camera_ray,
    shade_ray,
    sphere_quadric,
)


def srgb_8bit(linear):
    """Blender's Standard view transform on an sRGB display, then 8-bit quantisation."""
    c = np.clip(np.asarray(linear, float), 0.0, 1.0)
    encoded = np.where(c <= 0.0031308, 12.92 * c, 1.055 * c ** (1 / 2.4) - 0.055)
    return encoded * 255.0


def reference_scene(bpy_scene):
    """(camera, spheres, lights, world colour, width, height) of a scene of tagged spheres."""
    render = bpy_scene.render
    width = render.resolution_x * render.resolution_percentage // 100
    height = render.resolution_y * render.resolution_percentage // 100
    cam = bpy_scene.camera
    assert cam.data.sensor_fit == "AUTO" and width >= height
    tan_half_w = cam.data.sensor_width / 2 / cam.data.lens
    fovy = math.degrees(2 * math.atan(tan_half_w * height / width))
    rotation = np.array(cam.matrix_world)[:3, :3]
    camera = {
        "eye": np.array(cam.matrix_world)[:3, 3],
        "view": -rotation[:, 2],
        "up": rotation[:, 1],
        "fovy": fovy,
        # With sensor fit Auto, Orthographic Scale spans the larger side, here the width
        "ortho_height": cam.data.ortho_scale * height / width if cam.data.type == "ORTHO" else None,
    }
    spheres, lights = [], []
    for obj in bpy_scene.objects:
        if obj.type == "MESH" and obj.whitted.shape == "SPHERE":
            material = obj.active_material
            principled = next(n for n in material.node_tree.nodes if n.type == "BSDF_PRINCIPLED")
            spheres.append(
                {
                    "Q": sphere_quadric(np.array(obj.matrix_world)),
                    "kd": tuple(principled.inputs["Base Color"].default_value[:3]),
                    "ks": tuple(material.whitted.specular),
                    "p": material.whitted.shininess,
                }
            )
        elif obj.type == "LIGHT":
            data = obj.data
            lights.append(
                {
                    "position": np.array(obj.matrix_world)[:3, 3],
                    "intensity": np.array(data.color) * data.energy / (4 * math.pi**2),
                    "attenuation": tuple(data.whitted.attenuation),
                }
            )
    background = next(n for n in bpy_scene.world.node_tree.nodes if n.type == "BACKGROUND")
    world = np.array(background.inputs[0].default_value[:3]) * background.inputs[1].default_value
    return camera, spheres, lights, world, width, height


def expected_pixels(bpy_scene, pixels):
    """8-bit sRGB values (float) expected at each (px, py), py counted from the top."""
    camera, spheres, lights, world, width, height = reference_scene(bpy_scene)
    expected = []
    for px, py in pixels:
        if camera["ortho_height"] is not None:
            o, d = orthographic_camera_ray(
                camera["eye"], camera["view"], camera["up"], camera["ortho_height"], width,
                height, px, py,
            )  # fmt: skip
        else:
            o, d = camera_ray(
                camera["eye"], camera["view"], camera["up"], camera["fovy"], width, height, px, py
            )
        expected.append(srgb_8bit(shade_ray(spheres, lights, world, world, o, d)))
    return np.array(expected)


def sample_grid(width, height, step):
    return [(x, y) for y in range(step // 2, height, step) for x in range(step // 2, width, step)]
