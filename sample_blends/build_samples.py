"""Build the sample scenes from nothing. Run by `make samples`, with the Whitted add-on enabled:

    blender -b --factory-startup --addons whitted --python sample_blends/build_samples.py

Run it with the oldest supported Blender (3.4): files saved by Blender 5.0 do not open in 3.4,
while 3.4's open in both.
"""

import math
from pathlib import Path

import bpy

HERE = Path(__file__).resolve().parent


def clear_scene():
    bpy.ops.wm.read_factory_settings(use_empty=True)
    return bpy.context.scene


def make_material(name, base_colour, specular=(0.5, 0.5, 0.5), shininess=25.0):
    material = bpy.data.materials.new(name)
    material.use_nodes = True
    principled = next(n for n in material.node_tree.nodes if n.type == "BSDF_PRINCIPLED")
    principled.inputs["Base Color"].default_value = (*base_colour, 1.0)
    material.diffuse_color = (*base_colour, 1.0)
    material.whitted.use_whitted = True  # the report's Phong values, not the Principled mapping
    material.whitted.specular = specular
    material.whitted.shininess = shininess
    return material


def add_sphere(scene, name, location, radius, material):
    bpy.ops.mesh.primitive_uv_sphere_add(radius=1.0, location=location, segments=48, ring_count=24)
    obj = bpy.context.object
    obj.name = name
    obj.scale = (radius, radius, radius)
    obj.whitted.shape = "SPHERE"
    obj.data.materials.append(material)
    bpy.ops.object.shade_smooth()
    return obj


def configure_render(scene, width, height):
    scene.render.engine = "WHITTED"
    scene.render.resolution_x = width
    scene.render.resolution_y = height
    scene.render.resolution_percentage = 100
    scene.render.image_settings.file_format = "PNG"
    scene.render.image_settings.color_mode = "RGBA"
    # Standard view transform and no dither: 8-bit output is the sRGB encoding of the linear
    # render, so tests can predict pixel values exactly.
    scene.view_settings.view_transform = "Standard"
    scene.view_settings.look = "None"
    scene.render.dither_intensity = 0.0


def set_world(scene, colour):
    world = bpy.data.worlds.new("World")
    world.use_nodes = True
    background = next(n for n in world.node_tree.nodes if n.type == "BACKGROUND")
    background.inputs[0].default_value = (*colour, 1.0)
    background.inputs[1].default_value = 1.0
    world.color = colour
    scene.world = world


def build_spheres():
    """Three spheres on a huge ground sphere, one point light: the foundation's sample."""
    scene = clear_scene()
    configure_render(scene, 320, 240)
    set_world(scene, (0.05, 0.07, 0.1))

    ground = make_material("Ground", (0.6, 0.6, 0.6), specular=(0.0, 0.0, 0.0), shininess=1.0)
    add_sphere(scene, "Ground", (0.0, 0.0, -1000.0), 1000.0, ground)
    add_sphere(scene, "Red", (-2.2, 0.0, 1.0), 1.0, make_material("Red", (0.8, 0.1, 0.1)))
    add_sphere(scene, "Green", (0.0, 1.5, 1.0), 1.0, make_material("Green", (0.1, 0.7, 0.2)))
    add_sphere(scene, "Blue", (2.2, 0.0, 1.0), 1.0, make_material("Blue", (0.1, 0.2, 0.8)))

    light_data = bpy.data.lights.new("Key", type="POINT")
    light_data.energy = 2000.0
    light_data.whitted.attenuation = (0.0, 0.0, 1.0)
    light = bpy.data.objects.new("Key", light_data)
    light.location = (3.0, -4.0, 8.0)
    scene.collection.objects.link(light)

    camera_data = bpy.data.cameras.new("Camera")
    camera_data.lens = 35.0
    camera = bpy.data.objects.new("Camera", camera_data)
    camera.location = (0.0, -11.0, 4.5)
    camera.rotation_euler = (math.radians(72.0), 0.0, 0.0)
    scene.collection.objects.link(camera)
    scene.camera = camera

    bpy.ops.wm.save_as_mainfile(filepath=str(HERE / "spheres.blend"), compress=True)


if __name__ == "__main__":
    build_spheres()
