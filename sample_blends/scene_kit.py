"""Building blocks for the sample scenes (run inside Blender with the Whitted add-on).

Everything is made the way a user would make it: Blender primitives tagged as exact shapes,
Boolean modifiers for CSG, materials with the Whitted panel's values, Blender lights and
cameras. Colours and intensities are the report's: a light of intensity I has colour (1,1,1)
and the power that the add-on turns back into I.
"""

from __future__ import annotations

import importlib
import math
from pathlib import Path

import addon_utils
import bpy
import numpy as np
from mathutils import Matrix, Vector

HERE = Path(__file__).resolve().parent
# Where save() writes and image() reads the textures: this folder, or another given to
# build_samples.py (the test that the script rebuilds the committed files)
OUTPUT = HERE
# The add-on's point-light intensity is colour x power / (4 pi^2), as Cycles makes it
WATTS_PER_INTENSITY = 4.0 * math.pi**2


def new_file():
    """An empty file with one scene, the add-on still enabled."""
    bpy.ops.wm.read_factory_settings(use_empty=True)
    addon_utils.enable("whitted", default_set=True)  # factory settings unloaded it
    bpy.context.preferences.filepaths.save_version = 0  # no .blend1 backups
    return bpy.context.scene


def frame_views(scene) -> None:
    """Every 3D view of the file looks through the scene's camera, with clip distances that fit
    the scene: Blender's own (1 cm to 1 km) left the final scene, a few hundred metres across,
    clipped, and a new file opened with the view inside an object. Orbiting out of the camera
    view circles the scene's middle at a distance that shows all of it."""
    bpy.context.view_layer.update()  # world matrices of objects placed since the last update
    corners = np.array(
        [
            obj.matrix_world @ Vector(corner)
            for obj in scene.objects
            if obj.type == "MESH"
            for corner in obj.bound_box
        ]  # fmt: skip
    )
    low, high = corners.min(axis=0), corners.max(axis=0)
    extent = float(np.linalg.norm(high - low))
    for screen in bpy.data.screens:
        for area in screen.areas:
            if area.type != "VIEW_3D":
                continue
            space = area.spaces.active
            space.clip_end = max(1000.0, 4.0 * extent)
            space.clip_start = space.clip_end * 1e-5
            view = space.region_3d
            view.view_location = Vector(((low + high) / 2.0).tolist())
            view.view_distance = extent
            if scene.camera is not None:
                view.view_perspective = "CAMERA"


def save(name: str) -> Path:
    frame_views(bpy.context.scene)
    path = OUTPUT / name
    bpy.ops.wm.save_as_mainfile(filepath=str(path), compress=True)
    bpy.ops.file.make_paths_relative()  # textures as //textures/..., next to the file
    bpy.ops.wm.save_mainfile(compress=True)
    return path


def image(name: str):
    """A texture from the output's textures/ folder (made relative to the .blend by save)."""
    return bpy.data.images.load(str(OUTPUT / "textures" / name), check_existing=True)


def _builder():
    """The add-on's builder of Blender data (Blender's --addons whitted, or the bpy module's
    registration, has loaded it as `whitted`): the samples are made as its Add menu and Lua
    importer make theirs."""
    return importlib.import_module("whitted.blender_data")


def material(name, diffuse=(0.7, 0.7, 0.7), specular=(0.3, 0.3, 0.3), shininess=25.0,
             reflectivity=0.0, transparency=0.0, inner_ior=1.5, texture=None):  # fmt: skip
    """A material with the Whitted panel switched on (the report's gr.material values); the
    Principled BSDF gets the same base colour and texture, for the viewport."""
    return _builder().whitted_material(
        name, diffuse, specular, shininess, reflectivity, transparency, outer_ior=1.0,
        inner_ior=inner_ior, image=None if texture is None else image(texture),
    )  # fmt: skip


# Segments around and along the stand-ins: finer than the Add menu's, for the screenshots
_DETAIL = {"SPHERE": (48, 24), "CYLINDER": (64, 1), "CONE": (64, 1), "TORUS": (64, 24)}


def shape(kind, name, mat=None, location=(0, 0, 0), rotation=(0, 0, 0), scale=(1, 1, 1),
          collection=None, major_radius=1.0, minor_radius=0.25):  # fmt: skip
    """A stand-in of that kind, tagged as Whitted's exact shape. Rotation in degrees (XYZ
    Euler). A torus's radii are its own (the object's scale comes on top)."""
    builder = _builder()
    radii = (major_radius, minor_radius)
    around, along = _DETAIL.get(kind, (None, None))
    mesh = builder.stand_in(kind, name, radii, around, along)
    obj = builder.shape_object(kind, name, radii, mesh=mesh)
    obj.location = location
    obj.rotation_euler = [math.radians(a) for a in rotation]
    obj.scale = scale
    if mat is not None:
        obj.data.materials.append(mat)
    (collection or bpy.context.scene.collection).objects.link(obj)
    return obj


def mesh_object(name, vertices, triangles, corner_uvs=None, smooth=True, mat=None,
                location=(0, 0, 0), rotation=(0, 0, 0), scale=(1, 1, 1),
                collection=None):  # fmt: skip
    """A mesh object from numpy vertices (v, 3) and triangles (t, 3), with optional corner UVs
    (t, 3, 2); every face smooth or every face flat."""
    mesh = _builder().triangle_mesh_data(name, vertices, triangles, corner_uvs, smooth)
    if mat is not None:
        mesh.materials.append(mat)
    obj = bpy.data.objects.new(name, mesh)
    obj.location = location
    obj.rotation_euler = [math.radians(a) for a in rotation]
    obj.scale = scale
    (collection or bpy.context.scene.collection).objects.link(obj)
    return obj


def floor_plane(name, mat, x_range, y_range, tile, z=0.0):
    """A horizontal rectangle of two triangles whose UVs repeat the texture every `tile`
    units (a tagged cube's UVs would stretch one copy across each face)."""
    (x0, x1), (y0, y1) = x_range, y_range
    corners = np.array([[x0, y0, 0.0], [x1, y0, 0.0], [x1, y1, 0.0], [x0, y1, 0.0]])
    triangles = np.array([[0, 1, 2], [0, 2, 3]])
    return mesh_object(name, corners, triangles, corners[triangles][..., :2] / tile,
                       smooth=False, mat=mat, location=(0, 0, z))  # fmt: skip


def boolean(target, operation, operand):
    """A Boolean modifier (UNION, INTERSECT or DIFFERENCE) with the operand hidden from
    rendering, as a Blender user does with a cutter: Whitted renders the exact CSG."""
    return _builder().add_boolean(target, operation, operand)


def move_to(obj, collection):
    if collection is None:
        return
    for owner in list(obj.users_collection):
        owner.objects.unlink(obj)
    collection.objects.link(obj)


def point_light(name, location, intensity=1.0, attenuation=(1.0, 0.0, 0.0), collection=None):
    data = bpy.data.lights.new(name, "POINT")
    data.energy = intensity * WATTS_PER_INTENSITY
    data.shadow_soft_size = 0.0
    data.whitted.model = "CS488"
    data.whitted.attenuation = attenuation
    return _link(bpy.data.objects.new(name, data), location, collection)


def area_light(name, location, size, intensity=1.0, attenuation=(1.0, 0.0, 0.0),
               rotation=(0, 0, 0), collection=None):  # fmt: skip
    """A square area light of edge `size`, facing down (its -Z) unless rotated."""
    data = bpy.data.lights.new(name, "AREA")
    data.shape = "SQUARE"
    data.size = size
    data.energy = intensity * WATTS_PER_INTENSITY
    data.whitted.model = "CS488"
    data.whitted.attenuation = attenuation
    obj = _link(bpy.data.objects.new(name, data), location, collection)
    obj.rotation_euler = [math.radians(a) for a in rotation]
    return obj


def camera(name, eye, target, fovy=50.0, up=(0, 0, 1), scene=None, collection=None):
    """A camera at `eye` looking at `target`, with a vertical field of view of `fovy` degrees
    (the report's gr.render camera), made the scene's camera."""
    data = bpy.data.cameras.new(name)
    data.sensor_fit = "VERTICAL"
    data.angle_y = math.radians(fovy)
    data.clip_end = 1e5
    obj = _link(bpy.data.objects.new(name, data), eye, collection)
    forward = (Vector(target) - Vector(eye)).normalized()
    right = forward.cross(Vector(up)).normalized()
    true_up = right.cross(forward)
    obj.matrix_world = (
        Matrix.Translation(eye)
        @ Matrix([(*right, 0), (*true_up, 0), (*(-forward), 0), (0, 0, 0, 1)]).transposed()
    )
    scene = scene or bpy.context.scene
    scene.camera = obj
    return obj


def _link(obj, location, collection):
    obj.location = location
    (collection or bpy.context.scene.collection).objects.link(obj)
    return obj


def world(scene, colour):
    """The world colour as the report used it: Whitted's ambient light and the background
    (the CS488 World Model: the World lights nothing itself)."""
    w = bpy.data.worlds.new(f"{scene.name} World")
    w.use_nodes = True
    background = next(n for n in w.node_tree.nodes if n.type == "BACKGROUND")
    background.inputs[0].default_value = (*colour, 1.0)
    background.inputs[1].default_value = 1.0
    w.color = colour
    w.whitted.model = "CS488"
    w.whitted.ambient = colour
    scene.world = w
    return w


def configure(scene, width, height, pixel_samples=1, shadow_samples=16, max_depth=5):
    scene.render.engine = "WHITTED"
    scene.render.resolution_x, scene.render.resolution_y = width, height
    scene.render.resolution_percentage = 100
    scene.render.image_settings.file_format = "PNG"
    scene.render.image_settings.color_mode = "RGBA"
    # Standard view transform and no dither: 8-bit output is the sRGB encoding of the linear
    # render, so tests can predict pixel values exactly
    scene.view_settings.view_transform = "Standard"
    scene.view_settings.look = "None"
    scene.render.dither_intensity = 0.0
    settings = scene.whitted
    settings.pixel_samples = pixel_samples
    settings.pixel_sampling = "GRID"
    settings.shadow_samples = shadow_samples
    settings.shadow_sampling = "STRATIFIED"
    settings.max_depth = max_depth
    # the report's scenes keep its pictures: its pale shadow through glass, no caustics (as
    # the Lua importer sets them; Render > Light Paths turns them on)
    settings.glass_shadows = "ATTENUATED"
    settings.use_caustics_reflective = settings.use_caustics_refractive = False


def variant(stage, name):
    """Another scene in the same file showing `stage` (a collection) under its own camera and
    settings: how one file holds a feature's off/on or focus variants."""
    scene = bpy.data.scenes.new(name)
    scene.collection.children.link(stage)
    return scene
