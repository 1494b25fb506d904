"""Build the sample scenes from nothing. Run by `make samples`, with the Whitted add-on enabled:

    blender -b --factory-startup --addons whitted --python sample_blends/build_samples.py \
        [-- OUTPUT_FOLDER]

One .blend per feature of the report, shown the way its figures show it; a feature with
variants (supersampling off and on, three focus distances, hard and soft shadow) keeps them as
scenes of one file, sharing the objects (render one with `blender -b file -S "Scene name"`).
Textures come from textures.py, the teapot from teapot.py. Run it with the oldest supported
Blender (3.4): files saved by Blender 5.0 do not open in 3.4, while 3.4's open in both.
"""

import math
import sys
from pathlib import Path

import bpy

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))  # the helpers next to this script

import final_scene  # noqa: E402
import scene_kit as kit  # noqa: E402
import teapot  # noqa: E402
import textures  # noqa: E402

KINDS = ("SPHERE", "CUBE", "CYLINDER", "CONE", "TORUS", "MESH")


def build_spheres():
    """Three spheres on a huge ground sphere, one point light: the foundation's sample."""
    scene = kit.new_file()
    kit.configure(scene, 320, 240)
    kit.world(scene, (0.05, 0.07, 0.1))
    ground = kit.material("Ground", (0.6, 0.6, 0.6), specular=(0.0, 0.0, 0.0), shininess=1.0)
    kit.shape("SPHERE", "Ground", ground, (0.0, 0.0, -1000.0), scale=(1000,) * 3)
    for name, x, y, colour in (
        ("Red", -2.2, 0.0, (0.8, 0.1, 0.1)),
        ("Green", 0.0, 1.5, (0.1, 0.7, 0.2)),
        ("Blue", 2.2, 0.0, (0.1, 0.2, 0.8)),
    ):
        mat = kit.material(name, colour, specular=(0.5, 0.5, 0.5), shininess=25.0)
        kit.shape("SPHERE", name, mat, (x, y, 1.0))
    kit.point_light("Key", (3.0, -4.0, 8.0), 2000.0 / kit.WATTS_PER_INTENSITY, (0.0, 0.0, 1.0))
    camera_data = bpy.data.cameras.new("Camera")
    camera_data.lens = 35.0
    camera_data.clip_end = 1e4  # past the ground sphere, 2 km across
    camera = bpy.data.objects.new("Camera", camera_data)
    camera.location = (0.0, -11.0, 4.5)
    camera.rotation_euler = (math.radians(72.0), 0.0, 0.0)
    scene.collection.objects.link(camera)
    scene.camera = camera
    kit.save("spheres.blend")


def _floor(name, mat, half=30.0, tile=2.0):
    """A square floor at z = 0 whose texture repeats every `tile` units."""
    return kit.floor_plane(name, mat, (-half, half), (-half, half), tile)


def _studio(scene, width, height, eye, target, fovy=40.0):
    kit.configure(scene, width, height)
    kit.world(scene, (0.15, 0.15, 0.17))
    kit.point_light("Key", (4.0, -6.0, 10.0), intensity=0.9)
    kit.camera("Camera", eye, target, fovy)


def _six_primitives(mats):
    """Sphere, cube, cylinder, cone, torus and a mesh (Blender's monkey), two rows of three."""
    spots = {"SPHERE": (-3, 2), "CUBE": (0, 2), "CYLINDER": (3, 2),
             "CONE": (-3, -1), "TORUS": (0, -1), "MESH": (3, -1)}  # fmt: skip
    for kind, (x, y) in spots.items():
        name = kind.title()
        if kind == "MESH":
            bpy.ops.mesh.primitive_monkey_add(calc_uvs=True, location=(x, y, 1.0))
            obj = bpy.context.object
            obj.name = "Mesh"
            obj.rotation_euler = (0.0, 0.0, math.radians(-20.0))
            bpy.ops.object.shade_smooth()
            obj.data.materials.append(mats[kind])
        elif kind == "TORUS":
            kit.shape(kind, name, mats[kind], (x, y, 0.8), rotation=(60, 0, 0),
                      major_radius=1.0, minor_radius=0.35)  # fmt: skip
        else:
            rotation = (0, 0, 30) if kind == "CUBE" else (0, 0, 0)
            kit.shape(kind, name, mats[kind], (x, y, 1.0), rotation=rotation,
                      scale=(0.85, 0.85, 0.85) if kind == "CUBE" else (1, 1, 1))  # fmt: skip


def build_primitives():
    scene = kit.new_file()
    _studio(scene, 480, 320, eye=(0, -9.0, 5.0), target=(0, 0.5, 0.7), fovy=38.0)
    colours = {
        "SPHERE": (0.8, 0.15, 0.1), "CUBE": (0.9, 0.6, 0.1), "CYLINDER": (0.2, 0.7, 0.2),
        "CONE": (0.1, 0.5, 0.8), "TORUS": (0.5, 0.2, 0.8), "MESH": (0.3, 0.7, 0.7),
    }  # fmt: skip
    _six_primitives({k: kit.material(k.title(), c) for k, c in colours.items()})
    _floor("Floor", kit.material("Floor", (0.5, 0.5, 0.5), specular=(0, 0, 0)))
    kit.save("primitives.blend")


def build_texture_mapping():
    scene = kit.new_file()
    _studio(scene, 480, 320, eye=(0, -9.0, 5.0), target=(0, 0.5, 0.7), fovy=38.0)
    grid = kit.material("UV Grid", specular=(0.2, 0.2, 0.2), texture="uv_grid.png")
    _six_primitives({kind: grid for kind in KINDS})
    _floor("Floor", kit.material("Floor", (0.5, 0.5, 0.5), specular=(0, 0, 0)))
    kit.save("texture_mapping.blend")


def build_supersampling():
    """A sphere and a turned cube against a plain sky; matte (no highlight), so that every
    object pixel has its material's hue and only edge pixels can mix it with the sky."""
    first = kit.new_file()
    stage = bpy.data.collections.new("Stage")
    first.collection.children.link(stage)
    blue = kit.material("Blue", (0.1, 0.2, 0.8), specular=(0, 0, 0))
    red = kit.material("Red", (0.8, 0.1, 0.1), specular=(0, 0, 0))
    kit.shape("SPHERE", "Sphere", blue, (-1.3, 0, 0), collection=stage)
    kit.shape("CUBE", "Cube", red, (1.4, 0, 0), rotation=(25, 15, 35),
              scale=(0.8, 0.8, 0.8), collection=stage)  # fmt: skip
    kit.point_light("Key", (3.0, -6.0, 6.0), intensity=0.8, collection=stage)
    for scene, samples in ((first, 1), (kit.variant(stage, "Supersampling On"), 3)):
        if scene is first:
            scene.name = "Supersampling Off"
        kit.configure(scene, 160, 100, pixel_samples=samples)
        kit.world(scene, (0.55, 0.6, 0.65))
        kit.camera(f"Camera {samples}x{samples}", (0, -8, 1.5), (0, 0, 0), 30.0, scene=scene,
                   collection=stage if scene is first else scene.collection)  # fmt: skip
    kit.save("supersampling.blend")


def build_mirror():
    scene = kit.new_file()
    _studio(scene, 400, 300, eye=(0, -10, 4), target=(0, 0, 1), fovy=35.0)
    scene.whitted.max_depth = 8
    mirror = kit.material("Mirror", (0.05, 0.05, 0.05), specular=(0.8, 0.8, 0.8),
                          shininess=300.0, reflectivity=0.9)  # fmt: skip
    kit.shape("SPHERE", "Mirror Ball Left", mirror, (-1.3, 0.5, 1.2), scale=(1.2,) * 3)
    kit.shape("SPHERE", "Mirror Ball Right", mirror, (1.3, 1.0, 1.2), scale=(1.2,) * 3)
    kit.shape("SPHERE", "Red Ball", kit.material("Red", (0.8, 0.1, 0.1)), (0.9, -1.6, 0.6),
              scale=(0.6,) * 3)  # fmt: skip
    kit.shape("CUBE", "Green Box", kit.material("Green", (0.1, 0.7, 0.2)), (-1.6, -1.8, 0.5),
              rotation=(0, 0, 25), scale=(0.5,) * 3)  # fmt: skip
    _floor("Floor", kit.material("Checker", specular=(0, 0, 0), texture="checker.png"))
    kit.save("mirror.blend")


def build_refraction():
    """A glass ball (outer IOR 1, inner 1.53) in front of a wall, red on the left and blue on
    the right: a ball lens shows them swapped, upside down and left to right."""
    scene = kit.new_file()
    _studio(scene, 400, 300, eye=(0, -9, 1.5), target=(0, 0, 1.2), fovy=30.0)
    scene.whitted.max_depth = 10
    glass = kit.material("Glass", (0.02, 0.02, 0.02), specular=(0.9, 0.9, 0.9),
                         shininess=500.0, transparency=0.95, inner_ior=1.53)  # fmt: skip
    kit.shape("SPHERE", "Glass Ball", glass, (0, 0, 1.2), scale=(1.1,) * 3)
    kit.shape("CUBE", "Red Wall", kit.material("Red Wall", (0.8, 0.1, 0.1), specular=(0, 0, 0)),
              (-2.5, 5.0, 2.0), scale=(2.5, 0.1, 3.0))  # fmt: skip
    kit.shape("CUBE", "Blue Wall", kit.material("Blue Wall", (0.1, 0.2, 0.8), specular=(0, 0, 0)),
              (2.5, 5.0, 2.0), scale=(2.5, 0.1, 3.0))  # fmt: skip
    _floor("Floor", kit.material("Checker", specular=(0, 0, 0), texture="checker.png"))
    kit.save("refraction.blend")


def build_csg():
    """The report's three CSG figures, left to right: sphere ∩ cube, the union of three
    cylinders, cube − cylinder (bored along the view, so the floor shows through)."""
    scene = kit.new_file()
    _studio(scene, 480, 220, eye=(0, -11, 2.5), target=(0, 0, 1.1), fovy=26.0)
    steel = kit.material("Steel Blue", (0.3, 0.45, 0.7), shininess=40.0)
    amber = kit.material("Amber", (0.85, 0.55, 0.1), shininess=40.0)
    green = kit.material("Green", (0.2, 0.65, 0.3), shininess=40.0)
    cube = kit.shape("CUBE", "Sphere And Cube", steel, (-3.2, 0, 1.2), rotation=(0, 0, 30))
    sphere = kit.shape("SPHERE", "Rounding Sphere", steel, (-3.2, 0, 1.2), scale=(1.35,) * 3)
    kit.boolean(cube, "INTERSECT", sphere)
    jack = kit.shape("CYLINDER", "Three Cylinders", amber, (0, 0, 1.2), rotation=(20, 30, 0),
                     scale=(0.45, 0.45, 1.2))  # fmt: skip
    for i, rotation in enumerate(((90, 0, 0), (0, 90, 0))):
        arm = kit.shape("CYLINDER", f"Cylinder Arm {i + 1}", amber, (0, 0, 1.2),
                        rotation=rotation, scale=(0.45, 0.45, 1.2))  # fmt: skip
        arm.parent = jack
        arm.matrix_parent_inverse = jack.matrix_world.inverted()
        kit.boolean(jack, "UNION", arm)
    block = kit.shape("CUBE", "Bored Cube", green, (3.2, 0, 1.2), rotation=(0, 0, 0))
    bore = kit.shape("CYLINDER", "Bore", green, (3.2, 0, 1.2), rotation=(90, 0, 0),
                     scale=(0.55, 0.55, 1.5))  # fmt: skip
    kit.boolean(block, "DIFFERENCE", bore)
    _floor("Floor", kit.material("Floor", (0.5, 0.5, 0.5), specular=(0, 0, 0)))
    kit.save("csg.blend")


# The report's torus-shadow figure, in its units: a 50 x 50 area light above a torus
SHADOW_LIGHT_HEIGHT, TORUS_HEIGHT, TORUS_RADII = 400.0, 100.0, (60.0, 20.0)


def build_soft_shadow():
    first = kit.new_file()
    first.name = "Hard Shadow"
    stage = bpy.data.collections.new("Stage")
    first.collection.children.link(stage)
    white = kit.material("White", (0.8, 0.8, 0.8), specular=(0.4, 0.4, 0.4), shininess=40.0)
    major, minor = TORUS_RADII
    kit.shape("TORUS", "Torus", white, (0, 0, TORUS_HEIGHT), major_radius=major,
              minor_radius=minor, collection=stage)  # fmt: skip
    floor = _floor("Floor", kit.material("Floor", (0.7, 0.7, 0.7), specular=(0, 0, 0)),
                   half=1000.0)  # fmt: skip
    kit.move_to(floor, stage)
    soft = kit.variant(stage, "Soft Shadow")
    for scene in (first, soft):
        kit.configure(scene, 320, 240, shadow_samples=60)
        kit.world(scene, (0.1, 0.1, 0.1))
        kit.camera(f"{scene.name} Camera", (0, -520, 420), (0, 0, 40), 40.0, scene=scene,
                   collection=scene.collection)  # fmt: skip
    position = (0.0, 0.0, SHADOW_LIGHT_HEIGHT)
    kit.point_light("Point Light", position, intensity=1.0, collection=first.collection)
    kit.area_light("Area Light 50x50", position, 50.0, intensity=1.0, collection=soft.collection)
    kit.save("soft_shadow.blend")


DOF_SPHERES = (("Front", (-1.6, -3.0, 1.0)), ("Middle", (0.0, 1.0, 1.0)),
               ("Back", (1.8, 5.0, 1.0)))  # fmt: skip
DOF_APERTURE_RADIUS = 0.3


def build_depth_of_field():
    """Three checkered spheres at different depths; one scene focused on each."""
    first = kit.new_file()
    stage = bpy.data.collections.new("Stage")
    first.collection.children.link(stage)
    checker = kit.material("Checker Ball", specular=(0.3, 0.3, 0.3), texture="uv_grid.png")
    spheres = {name: kit.shape("SPHERE", f"{name} Sphere", checker, spot, collection=stage)
               for name, spot in DOF_SPHERES}  # fmt: skip
    floor = _floor("Floor", kit.material("Floor Checker", specular=(0, 0, 0),
                                         texture="checker.png"))  # fmt: skip
    kit.move_to(floor, stage)
    kit.point_light("Key", (4.0, -6.0, 10.0), intensity=0.9, collection=stage)
    for i, (name, _) in enumerate(DOF_SPHERES):
        scene = first if i == 0 else kit.variant(stage, f"Focus {name}")
        scene.name = f"Focus {name}"
        kit.configure(scene, 320, 200, pixel_samples=6)
        scene.whitted.pixel_sampling = "JITTERED"
        kit.world(scene, (0.15, 0.15, 0.17))
        cam = kit.camera(f"Camera Focus {name}", (0, -12, 2.2), (0, 0, 1.0), 28.0, scene=scene,
                         collection=scene.collection)  # fmt: skip
        cam.data.dof.use_dof = True
        cam.data.dof.focus_object = spheres[name]
        # Cycles' aperture: radius = focal length / (2 f-stop)
        cam.data.dof.aperture_fstop = cam.data.lens * 1e-3 / (2.0 * DOF_APERTURE_RADIUS)
    kit.save("depth_of_field.blend")


def build_teapot():
    """Newell's teapot twice: flat-shaded on the left, smooth (Phong) on the right."""
    scene = kit.new_file()
    _studio(scene, 400, 200, eye=(0, -14, 5), target=(0, 0, 1.3), fovy=30.0)
    mesh = teapot.tessellate(segments=10)
    for name, x, smooth in (("Teapot Flat", -3.4, False), ("Teapot Smooth", 3.4, True)):
        porcelain = kit.material(name, (0.7, 0.12, 0.08), specular=(0.7, 0.7, 0.7),
                                 shininess=60.0)  # fmt: skip
        kit.mesh_object(name, mesh.vertices, mesh.triangles, mesh.corner_uvs, smooth=smooth,
                        mat=porcelain, location=(x, 0, 0), rotation=(0, 0, -20))  # fmt: skip
    _floor("Floor", kit.material("Floor", (0.5, 0.5, 0.5), specular=(0, 0, 0)))
    kit.save("teapot.blend")


def build_final_scene():
    final_scene.build()
    kit.save("final_scene.blend")


BUILDERS = (
    build_spheres, build_primitives, build_texture_mapping, build_supersampling, build_mirror,
    build_refraction, build_csg, build_soft_shadow, build_depth_of_field, build_teapot,
    build_final_scene,
)  # fmt: skip

if __name__ == "__main__":
    arguments = sys.argv[sys.argv.index("--") + 1 :] if "--" in sys.argv else []
    if arguments:
        kit.OUTPUT = Path(arguments[0]).resolve()
    textures.write_all(kit.OUTPUT / "textures")
    for builder in BUILDERS:
        builder()
