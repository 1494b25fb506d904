"""The report's final scene, built as Blender data (run through build_samples.py).

Report units and layout ideas: a wooden table (a cube minus a sphere, here an ellipsoid so
that legs and arches remain), a mug and a bowl (a cylinder minus a smaller one), an ice-cream
cone with a waffle texture and a sphere of ice cream on two white tori, Newell's teapot
smooth-shaded, a wooden floor, a mirror back wall, one 50 x 50 area light with 40 shadow
rays, 3 x 3 supersampling, recursion depth 50, 500 x 500. Blender is z-up: the report's
y (up) is our z, its z (towards the eye) is our -y.
"""

from __future__ import annotations

import scene_kit as kit
import teapot

TABLE_TOP = -60.0  # z of the table's top face
FLOOR = -250.0


def build(width=500, height=500):
    scene = kit.new_file()
    scene.name = "Final Scene"
    kit.configure(scene, width, height, pixel_samples=3, shadow_samples=40, max_depth=50)
    kit.world(scene, (0.3, 0.3, 0.3))  # the report's ambient 0.3
    _room()
    _table()
    _mug_and_bowl()
    _ice_cream()
    _teapot()
    kit.area_light("Area Light", (0.0, -400.0, 400.0), size=50.0, intensity=0.9)
    kit.camera("Camera", eye=(0.0, -850.0, 280.0), target=(0.0, 20.0, -90.0), fovy=50.0)
    return scene


def _room():
    wood = kit.material(
        "Floor Wood", specular=(0.15, 0.15, 0.15), shininess=15.0, texture="wood_floor.png"
    )
    kit.floor_plane("Floor", wood, (-1600.0, 1600.0), (-1200.0, 400.0), tile=400.0, z=FLOOR)
    mirror = kit.material(
        "Mirror", diffuse=(0.05, 0.05, 0.06), specular=(0.8, 0.8, 0.8), shininess=200.0,
        reflectivity=0.85,
    )  # fmt: skip
    kit.shape("CUBE", "Mirror Wall", mirror, location=(0, 410, 300), scale=(1600, 10, 550))


def _table():
    wood = kit.material(
        "Table Wood", specular=(0.3, 0.3, 0.3), shininess=30.0, texture="wood_table.png"
    )
    depth = (TABLE_TOP - FLOOR) / 2.0
    table = kit.shape("CUBE", "Table", wood, location=(0, 0, FLOOR + depth),
                      scale=(330, 190, depth))  # fmt: skip
    carve = kit.shape("SPHERE", "Table Carve", wood, location=(0, 0, FLOOR),
                      scale=(300, 250, 170))  # fmt: skip
    kit.boolean(table, "DIFFERENCE", carve)


def _cup(name, mat, x, y, radius, height, wall, floor):
    """A cylinder minus a smaller cylinder that leaves a wall and a floor: the mug and bowl."""
    body = kit.shape("CYLINDER", name, mat, location=(x, y, TABLE_TOP + height / 2),
                     scale=(radius, radius, height / 2))  # fmt: skip
    hollow = kit.shape(
        "CYLINDER", f"{name} Hollow", mat,
        location=(x, y, TABLE_TOP + floor + height / 2),
        scale=(radius - wall, radius - wall, height / 2),
    )  # fmt: skip
    kit.boolean(body, "DIFFERENCE", hollow)
    return body


def _mug_and_bowl():
    blue = kit.material(
        "Mug Glaze", diffuse=(0.12, 0.25, 0.65), specular=(0.7, 0.7, 0.7), shininess=80.0,
        reflectivity=0.1,
    )  # fmt: skip
    _cup("Mug", blue, -235.0, -40.0, radius=45.0, height=100.0, wall=7.0, floor=10.0)
    cream = kit.material(
        "Bowl Glaze", diffuse=(0.85, 0.8, 0.65), specular=(0.6, 0.6, 0.6), shininess=60.0,
        reflectivity=0.15,
    )  # fmt: skip
    _cup("Bowl", cream, 225.0, 60.0, radius=85.0, height=45.0, wall=6.0, floor=8.0)


def _ice_cream():
    white = kit.material("Stand White", diffuse=(0.9, 0.9, 0.9), specular=(0.5, 0.5, 0.5),
                         shininess=40.0)  # fmt: skip
    x, y = 110.0, -120.0
    kit.shape("TORUS", "Stand Lower", white, location=(x, y, TABLE_TOP + 6.0),
              major_radius=20.0, minor_radius=6.0)  # fmt: skip
    kit.shape("TORUS", "Stand Upper", white, location=(x, y, TABLE_TOP + 17.0),
              major_radius=16.0, minor_radius=5.0)  # fmt: skip
    waffle = kit.material("Waffle", specular=(0.1, 0.1, 0.1), shininess=10.0, texture="waffle.png")
    # Blender's cone has its base at z = -1: turned over, the apex points down
    apex, length, radius = TABLE_TOP + 8.0, 130.0, 30.0
    kit.shape("CONE", "Cone", waffle, location=(x, y, apex + length / 2),
              rotation=(180, 0, 0), scale=(radius, radius, length / 2))  # fmt: skip
    strawberry = kit.material(
        "Ice Cream", diffuse=(0.95, 0.55, 0.65), specular=(0.4, 0.4, 0.4), shininess=30.0
    )
    kit.shape("SPHERE", "Ice Cream", strawberry, location=(x, y, apex + length + 14.0),
              scale=(33, 33, 33))  # fmt: skip


def _teapot():
    porcelain = kit.material(
        "Teapot Porcelain", diffuse=(0.7, 0.12, 0.08), specular=(0.8, 0.8, 0.8),
        shininess=100.0, reflectivity=0.1,
    )  # fmt: skip
    mesh = teapot.tessellate(segments=10)
    kit.mesh_object("Teapot", mesh.vertices, mesh.triangles, mesh.corner_uvs, smooth=True,
                    mat=porcelain, location=(-50.0, 70.0, TABLE_TOP), rotation=(0, 0, -30),
                    scale=(36, 36, 36))  # fmt: skip
