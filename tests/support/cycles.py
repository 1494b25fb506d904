"""Side by side with Cycles: the same Blender scene rendered by Cycles, set to compute the light
paths Whitted computes, and by Whitted, both read back as linear EXR pixels.

Cycles runs on the CPU with diffuse bounces 0 (a surface's colour is the light arriving at it
directly), glossy and transmission bounces 16, caustics on, Filter Glossy 0, the Standard view
transform, and a pixel filter 0.01 px wide, so that each pixel is the picture at its centre as
Whitted's one camera ray per pixel sees it. Runs in every Blender the tests run (3.4 to 5.2).
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from tests.support.exr import read_exr

SIZE = 32  # pixels across a test picture
VIEW = 8.0  # scene units the picture covers, seen straight down


def new_scene(bpy):
    """An empty scene with Whitted's add-on kept: a black World, an orthographic camera 10
    above the origin looking down at a white Lambertian plane z = 0, 20 units wide."""
    from tests.blender.conftest import clear_scene

    scene = clear_scene(bpy)
    for datablock in (bpy.data.lights, bpy.data.materials, bpy.data.cameras, bpy.data.worlds):
        for item in list(datablock):
            datablock.remove(item)
    scene.world = bpy.data.worlds.new("Black")
    scene.world.color = (0.0, 0.0, 0.0)
    if scene.world.node_tree is not None:
        scene.world.node_tree.nodes["Background"].inputs[1].default_value = 0.0
    render = scene.render
    render.resolution_x = render.resolution_y = SIZE
    render.resolution_percentage = 100
    render.use_border = False
    render.film_transparent = False
    render.image_settings.file_format = "OPEN_EXR"
    render.image_settings.color_depth = "32"
    scene.view_settings.view_transform = "Standard"
    camera = bpy.data.cameras.new("Camera")
    camera.type, camera.ortho_scale = "ORTHO", VIEW
    camera_object = bpy.data.objects.new("Camera", camera)
    scene.collection.objects.link(camera_object)
    camera_object.location = (0.0, 0.0, 10.0)
    scene.camera = camera_object
    plane = bpy.data.meshes.new("Plane")
    plane.from_pydata([(-10, -10, 0), (10, -10, 0), (10, 10, 0), (-10, 10, 0)], [], [(0, 1, 2, 3)])
    plane.materials.append(white_lambertian(bpy))
    scene.collection.objects.link(bpy.data.objects.new("Plane", plane))
    scene.whitted.pixel_samples = 1
    scene.whitted.shadow_samples = 256
    return scene


def white_lambertian(bpy):
    """A Diffuse BSDF of albedo 1. (Whitted reads it through its Material panel, Phong
    specular off, until node materials are read.)"""
    material = bpy.data.materials.new("White")
    material.use_nodes = True
    nodes = material.node_tree.nodes
    nodes.clear()
    diffuse = nodes.new("ShaderNodeBsdfDiffuse")
    diffuse.inputs["Color"].default_value = (1.0, 1.0, 1.0, 1.0)
    output = nodes.new("ShaderNodeOutputMaterial")
    material.node_tree.links.new(diffuse.outputs[0], output.inputs[0])
    material.diffuse_color = (1.0, 1.0, 1.0, 1.0)
    material.whitted.use_whitted = True
    material.whitted.specular = (0.0, 0.0, 0.0)
    return material


def add_light(bpy, scene, kind, location, rotation=(0.0, 0.0, 0.0), scale=(1, 1, 1), **fields):
    data = bpy.data.lights.new(kind.title(), kind)
    for name, value in fields.items():
        setattr(data, name, value)
    obj = bpy.data.objects.new(kind.title(), data)
    scene.collection.objects.link(obj)
    obj.location, obj.rotation_euler, obj.scale = location, rotation, scale
    return obj


def render_with(bpy, scene, engine: str, path: Path, samples: int = 256) -> np.ndarray:
    """The scene's linear RGB by `engine` ("CYCLES" or "WHITTED"), (SIZE, SIZE, 3), row 0
    at the top."""
    scene.render.engine = engine
    if engine == "CYCLES":
        cycles = scene.cycles
        cycles.device = "CPU"
        cycles.samples = samples
        cycles.use_denoising = False
        cycles.diffuse_bounces = 0
        cycles.glossy_bounces = cycles.transmission_bounces = 16
        cycles.caustics_reflective = cycles.caustics_refractive = True
        cycles.blur_glossy = 0.0
        cycles.filter_width = 0.01
        if hasattr(cycles, "use_adaptive_sampling"):
            cycles.use_adaptive_sampling = False
        cycles.seed = 7
    scene.render.filepath = str(path)
    bpy.ops.render.render(write_still=True)
    channels, _ = read_exr(path)
    return np.stack([channels[c] for c in ("R", "G", "B")], axis=-1).astype(float)


def side_by_side(bpy, scene, folder: Path, samples: int = 1024):
    """(Cycles' picture, Whitted's) of the scene."""
    cycles = render_with(bpy, scene, "CYCLES", folder / "cycles.exr", samples)
    whitted = render_with(bpy, scene, "WHITTED", folder / "whitted.exr")
    return cycles, whitted


def block_means(image: np.ndarray, block: int = 4) -> np.ndarray:
    """Means of block x block squares: Cycles' noise averaged down, the light's shape kept."""
    h, w = image.shape[0] // block, image.shape[1] // block
    return image[: h * block, : w * block].reshape(h, block, w, block, -1).mean(axis=(1, 3))


def brightness_ratios(cycles: np.ndarray, whitted: np.ndarray, lit_share: float = 0.05):
    """Whitted's over Cycles' brightness in each 4 x 4 block lit above `lit_share` of the
    brightest (Cycles' dark blocks are noise), with the blocks' Cycles brightness."""
    c, w = block_means(cycles).sum(axis=-1), block_means(whitted).sum(axis=-1)
    lit = c > lit_share * c.max()
    return w[lit] / c[lit], c[lit]


def turned(degrees_x=0.0, degrees_y=0.0, degrees_z=0.0):
    return tuple(math.radians(a) for a in (degrees_x, degrees_y, degrees_z))
