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
    # Whitted's render settings at their defaults, whatever another test left (a Jittered
    # pixel pattern, a Uniform shadow pattern made these tests depend on their order)
    for prop in scene.whitted.bl_rna.properties:
        if not prop.is_readonly:
            scene.whitted.property_unset(prop.identifier)
    scene.whitted.pixel_samples = 1
    scene.whitted.pixel_sampling = "GRID"  # one ray through the pixel's centre, as Cycles'
    scene.whitted.shadow_samples = 256
    return scene


def white_lambertian(bpy):
    """A Diffuse BSDF of albedo 1 (both renderers read the node)."""
    material = bpy.data.materials.new("White")
    material.use_nodes = True
    nodes = material.node_tree.nodes
    nodes.clear()
    diffuse = nodes.new("ShaderNodeBsdfDiffuse")
    diffuse.inputs["Color"].default_value = (1.0, 1.0, 1.0, 1.0)
    output = nodes.new("ShaderNodeOutputMaterial")
    material.node_tree.links.new(diffuse.outputs[0], output.inputs[0])
    return material


def add_light(bpy, scene, kind, location, rotation=(0.0, 0.0, 0.0), scale=(1, 1, 1), **fields):
    data = bpy.data.lights.new(kind.title(), kind)
    for name, value in fields.items():
        setattr(data, name, value)
    obj = bpy.data.objects.new(kind.title(), data)
    scene.collection.objects.link(obj)
    obj.location, obj.rotation_euler, obj.scale = location, rotation, scale
    return obj


def render_with(bpy, scene, engine: str, path: Path, samples: int = 256,
                diffuse_bounces: int = 0) -> np.ndarray:  # fmt: skip
    """The scene's linear RGB by `engine` ("CYCLES" or "WHITTED"), (SIZE, SIZE, 3), row 0
    at the top. `diffuse_bounces` 1 lets Cycles draw caustics on diffuse surfaces (a path
    from the camera to a diffuse surface, then by mirrors or glass to a light)."""
    scene.render.engine = engine
    if engine == "CYCLES":
        cycles = scene.cycles
        cycles.device = "CPU"
        cycles.samples = samples
        cycles.use_denoising = False
        cycles.diffuse_bounces = diffuse_bounces
        cycles.glossy_bounces = cycles.transmission_bounces = 16
        cycles.caustics_reflective = cycles.caustics_refractive = True
        cycles.blur_glossy = 0.0
        # Clamp Indirect (10 by default) cuts a caustic's bright samples: energy lost
        cycles.sample_clamp_direct = cycles.sample_clamp_indirect = 0.0
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


def brightness_ratios(cycles: np.ndarray, whitted: np.ndarray, lit_share=0.05, block=4):
    """Whitted's over Cycles' brightness in each block x block square lit above `lit_share`
    of the brightest (Cycles' dark blocks are noise), with the blocks' Cycles brightness."""
    c = block_means(cycles, block).sum(axis=-1)
    w = block_means(whitted, block).sum(axis=-1)
    lit = c > lit_share * c.max()
    return w[lit] / c[lit], c[lit]


def turned(degrees_x=0.0, degrees_y=0.0, degrees_z=0.0):
    return tuple(math.radians(a) for a in (degrees_x, degrees_y, degrees_z))


def mirror(bpy):
    """A perfect mirror: a Glossy BSDF of roughness 0 (both renderers read the node)."""
    material = bpy.data.materials.new("Mirror")
    material.use_nodes = True
    nodes = material.node_tree.nodes
    nodes.clear()
    glossy = nodes.new("ShaderNodeBsdfGlossy")
    glossy.inputs["Color"].default_value = (1.0, 1.0, 1.0, 1.0)
    glossy.inputs["Roughness"].default_value = 0.0
    output = nodes.new("ShaderNodeOutputMaterial")
    material.node_tree.links.new(glossy.outputs[0], output.inputs[0])
    return material


def add_ball(bpy, scene, material, location=(0.0, 0.0, 1.0), radius=1.0):
    """A tagged sphere (exact in Whitted; Cycles renders its mesh, subdivided finely): a unit
    sphere's mesh scaled by `radius`, as Whitted's canonical sphere is placed."""
    mesh = bpy.data.meshes.new("Ball")
    import bmesh

    shape = bmesh.new()
    bmesh.ops.create_uvsphere(shape, u_segments=256, v_segments=128, radius=1.0)
    shape.to_mesh(mesh)
    shape.free()
    for polygon in mesh.polygons:
        polygon.use_smooth = True
    mesh.materials.append(material)
    obj = bpy.data.objects.new("Ball", mesh)
    scene.collection.objects.link(obj)
    obj.location, obj.scale = location, (radius,) * 3
    obj.whitted.shape = "SPHERE"
    return obj


def environment_world(bpy, scene, pixels: np.ndarray, turn_degrees: float = 0.0, strength=1.0):
    """The World as an Environment Texture of `pixels` (h, w, 3 linear, row 0 at the top),
    through a Mapping node turning it about Z, fed by Generated coordinates."""
    height, width = pixels.shape[:2]
    image = bpy.data.images.new("Sky", width, height, alpha=True, float_buffer=True)
    rgba = np.ones((height, width, 4), np.float32)
    rgba[..., :3] = pixels[::-1]  # Blender's rows run bottom-up
    image.pixels.foreach_set(rgba.ravel())
    image.pack()
    world = scene.world
    world.use_nodes = True
    tree = world.node_tree
    background = next(n for n in tree.nodes if n.type == "BACKGROUND")
    background.inputs["Strength"].default_value = strength
    texture = tree.nodes.new("ShaderNodeTexEnvironment")
    texture.image = image
    mapping = tree.nodes.new("ShaderNodeMapping")
    mapping.inputs["Rotation"].default_value = (0.0, 0.0, math.radians(turn_degrees))
    coordinates = tree.nodes.new("ShaderNodeTexCoord")
    tree.links.new(coordinates.outputs["Generated"], mapping.inputs["Vector"])
    tree.links.new(mapping.outputs["Vector"], texture.inputs["Vector"])
    tree.links.new(texture.outputs["Color"], background.inputs["Color"])
    return world


def normal_map_image(bpy, name, seed, across=(0.2, 0.8), up=(0.7, 1.0)):
    """A 4 x 4 float image of normal-map colours (Non-Color): each texel's red and green
    (its tilt across the surface) uniform in `across`, its blue (up) in `up`."""
    rng = np.random.default_rng(seed)
    image = bpy.data.images.new(name, 4, 4, alpha=True, float_buffer=True)
    image.colorspace_settings.name = "Non-Color"  # before the pixels: setting it reloads them
    rgba = np.ones((4, 4, 4), np.float32)
    rgba[..., 0:2] = rng.uniform(*across, (4, 4, 2))
    rgba[..., 2] = rng.uniform(*up, (4, 4))
    image.pixels.foreach_set(rgba.ravel())
    image.pack()
    return image


def uniform_world(scene, colour, strength=1.0):
    world = scene.world
    world.use_nodes = True
    background = next(n for n in world.node_tree.nodes if n.type == "BACKGROUND")
    background.inputs["Color"].default_value = (*colour, 1.0)
    background.inputs["Strength"].default_value = strength
    return world


def node_material(bpy, name, shader_type, renamed=None, **inputs):
    """A material of one shader node (bpy type name) into the Material Output, its inputs
    set by name (underscores for spaces; `renamed` maps tuples of names, as `set_inputs`);
    returns (material, the shader node)."""
    material = bpy.data.materials.new(name)
    material.use_nodes = True
    nodes = material.node_tree.nodes
    nodes.clear()
    shader = nodes.new(shader_type)
    set_inputs(shader, renamed, **inputs)
    output = nodes.new("ShaderNodeOutputMaterial")
    material.node_tree.links.new(shader.outputs[0], output.inputs[0])
    return material, shader


def set_inputs(node, renamed=None, **inputs):
    """Set a node's inputs by name; `renamed` maps tuples of names to values, the first name
    the node has taking it (names changed across versions: Transmission Weight was
    Transmission)."""
    for key, value in {**(renamed or {}), **inputs}.items():
        names = key if isinstance(key, tuple) else (key.replace("_", " "),)
        socket = next(node.inputs[n] for n in names if n in node.inputs)
        if isinstance(value, tuple) and len(value) == 3 and socket.type == "RGBA":
            value = (*value, 1.0)
        socket.default_value = value


def emissive_floor(bpy, scene, colours=((1.0, 0.2, 0.2), (0.2, 1.0, 0.2), (0.2, 0.2, 1.0),
                                        (1.0, 1.0, 0.2))):  # fmt: skip
    """Replace the plane by four emissive quadrants (Emission shaders, strength 1): a floor
    whose colour no shadow or light changes, seen in mirrors and through glass alike by
    both renderers. Its Ray Visibility > Diffuse is off, so that Cycles does not light
    diffuse surfaces with it (Whitted's emissive surfaces light nothing)."""
    bpy.data.objects.remove(bpy.data.objects["Plane"])
    quads = ((-10, -10), (0, -10), (0, 0), (-10, 0))
    for k, ((x, y), colour) in enumerate(zip(quads, colours, strict=True)):
        mesh = bpy.data.meshes.new(f"Floor{k}")
        mesh.from_pydata([(x, y, 0), (x + 10, y, 0), (x + 10, y + 10, 0), (x, y + 10, 0)], [],
                         [(0, 1, 2, 3)])  # fmt: skip
        material, _ = node_material(bpy, f"Glow{k}", "ShaderNodeEmission", Color=colour)
        mesh.materials.append(material)
        quad = bpy.data.objects.new(f"Floor{k}", mesh)
        quad.visible_diffuse = False
        scene.collection.objects.link(quad)
