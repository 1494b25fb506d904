"""Object instances -> core shapes: tagged exact shapes, CSG, meshes per material slot.

One `TriangleMesh` per distinct mesh, one `Material` per Blender material, and the warnings
for the user, collected over a depsgraph's instances.
"""

from __future__ import annotations

import numpy as np

from .. import core
from ..properties.shape_tags import BY_TAG
from . import csg, material
from .mesh import MeshCache

# core.Shape's flags and the Object properties they come from
RAY_VISIBILITY = (
    ("lights_diffuse", "visible_diffuse"),
    ("seen_by_camera", "visible_camera"),
    ("seen_in_mirrors", "visible_glossy"),
    ("seen_through_glass", "visible_transmission"),
)


class Exporter:
    """Collects shapes from object instances: one `TriangleMesh` per distinct mesh, one
    `Material` per Blender material, and the warnings for the user."""

    def __init__(self, depsgraph, mesh_cache: MeshCache):
        self.depsgraph = depsgraph
        self.mesh_cache = mesh_cache
        self.shapes: list = []
        self.warnings: list[str] = []
        self.materials: dict[str, core.Material] = {}
        self.meshes: dict = {}

    def warn(self, text: str) -> None:
        self.warnings.append(text)

    def add_instance(self, obj, matrix: np.ndarray, tags=None, holdout=False) -> None:
        """One object instance (evaluated) placed by `matrix`; `tags` is the object whose
        Whitted settings it has, when not `obj` itself (see `whitted_source`); `holdout`:
        camera rays see a hole there (Object > Visibility > Holdout, holdout collections)."""
        original = obj.original
        settings = (tags or obj).whitted
        # Object > Visibility > Ray Visibility > Shadow (Blender 3.0+; older files lack it)
        casts_shadows = bool(getattr(original, "visible_shadow", True))
        # What the passes say of it: Object > Relations > Pass Index, and the holdout
        marks = dict(casts_shadows=casts_shadows, holdout=holdout, pass_index=original.pass_index)
        # Object > Visibility > Ray Visibility > Camera, Glossy and Transmission
        for mark, name in RAY_VISIBILITY:
            marks[mark] = bool(getattr(original, name, True))
        if obj.type == "MESH" and csg.boolean_modifiers(original):
            shape = csg.convert(original, self, self.depsgraph)
        elif obj.type == "MESH" and settings.shape != "MESH":
            shape = self.base_shape(obj, settings)
        else:
            for slot, part in self._instance_mesh(obj).items():
                if len(part.triangles):
                    slot_material = self.material(obj, slot)
                    self.shapes.append(
                        core.Mesh(obj.name, slot_material, matrix, mesh=part, **marks)
                    )
            return
        shape.world_from_object = matrix
        for name, value in marks.items():
            setattr(shape, name, value)
        self.shapes.append(shape)

    def base_shape(self, obj, settings=None) -> core.Shape:
        """The object's own shape in its object space: its tagged primitive, or its mesh as
        it is before modifiers (the Boolean modifiers' input)."""
        settings = settings or obj.whitted
        material = self.material(obj)
        if settings.shape == "TORUS":
            return core.Torus(obj.name, material, major_radius=settings.major_radius,
                              minor_radius=settings.minor_radius)  # fmt: skip
        if settings.shape in BY_TAG:
            return BY_TAG[settings.shape].shape(obj.name, material)
        mesh = obj.original.data
        key = ("original", mesh.name_full)
        if key not in self.meshes:
            self.meshes[key] = self.mesh_cache.get(key, mesh, mesh.name)
        return core.Mesh(obj.name, material, mesh=self.meshes[key][0])

    def _instance_mesh(self, obj) -> dict:
        """The evaluated mesh of an instance by material slot, converted once per distinct
        mesh datablock (linked duplicates and instancers share it). Curves, text, surfaces
        and metaballs arrive here as the mesh instances Blender evaluates them to."""
        # Modifiers, or another object type, make a mesh of the object's own; otherwise
        # objects share their mesh data
        source = obj.original
        owner = source.name_full if len(obj.modifiers) or source.type != "MESH" else ""
        key = ("evaluated", owner, obj.data.original.name_full)
        if key not in self.meshes:
            self.meshes[key] = self.mesh_cache.get(key, obj.data, obj.data.name)
        return self.meshes[key][1]

    def material(self, obj, slot: int | None = None) -> core.Material:
        """The object's material in `slot`, or its active one."""
        blender_material = obj.active_material
        if slot is not None:
            slots = obj.material_slots
            blender_material = slots[slot].material if 0 <= slot < len(slots) else None
        key = blender_material.name if blender_material is not None else ""
        if key not in self.materials:
            self.materials[key] = material.convert(blender_material, self.warn)
        return self.materials[key]
