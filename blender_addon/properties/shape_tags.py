"""The exact shapes a mesh object can be tagged as, each with the Blender primitive that
stands in for it: listed once for the Object panel's Shape menu (`properties`), the export
(`export.instances`) and Add › Whitted (`ui.add_menu`,
through `blender_data.stand_in`). Each core shape matches the primitive Blender adds
with default settings, so tagging that primitive renders the exact shape where its mesh sits.
"""

from dataclasses import dataclass

from ..core.model.shapes import ANALYTIC_SHAPES, Box, Cone, Cylinder, Sphere, Torus


@dataclass(frozen=True)
class ShapeTag:
    tag: str  # the Shape menu's identifier, stored in .blend files: never rename one
    shape: type  # the core shape it renders as
    label: str
    description: str
    icon: str  # of the stand-in primitive in the Add menu


EXACT = (
    ShapeTag("SPHERE", Sphere, "Sphere", "Exact sphere of radius 1 (Blender's UV sphere)",
             "MESH_UVSPHERE"),
    ShapeTag("CUBE", Box, "Cube", "Exact cube from -1 to 1 on each axis (Blender's cube)",
             "MESH_CUBE"),
    ShapeTag("CYLINDER", Cylinder, "Cylinder",
             "Exact capped cylinder, radius 1, z from -1 to 1 (Blender's)",
             "MESH_CYLINDER"),
    ShapeTag("CONE", Cone, "Cone", "Exact cone, base radius 1 at z = -1, apex at z = 1 (Blender's)",
             "MESH_CONE"),
    ShapeTag("TORUS", Torus, "Torus",
             "Exact torus around the z axis (Blender's torus: radii 1 and 0.25)",
             "MESH_TORUS"),
)  # fmt: skip
assert {tag.shape for tag in EXACT} == set(ANALYTIC_SHAPES), "a core shape has no tag"
BY_TAG = {tag.tag: tag for tag in EXACT}

# The Shape menu: the object's own triangles, or one of the exact shapes
MENU_ITEMS = [
    ("MESH", "Mesh", "Render the object's mesh triangles (smooth or flat per face, UVs)"),
    *((tag.tag, tag.label, tag.description) for tag in EXACT),
]
