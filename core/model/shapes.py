"""The shapes of a scene: analytic primitives and triangle meshes.

Every shape has a name, a `Material` and `world_from_object`, a 4x4 affine matrix placing its
canonical object-space form in the world; any invertible affine transform is allowed,
non-uniform scale included. The canonical forms match Blender's own primitives (z up):

    Sphere    radius 1 about the origin
    Box       the cube [-1, 1]^3
    Cylinder  radius 1 about the z axis, z in [-1, 1], both ends capped
    Cone      base radius 1 at z = -1 (capped), apex at z = +1
    Torus     about the z axis: a tube of radius `minor_radius` around a circle of radius
              `major_radius` in the xy plane
    Mesh      triangles of a `TriangleMesh`; meshes that share one `TriangleMesh` object are
              instances, and share its triangles and BVH
    Csg       union, intersection or difference of two shapes (see `Csg`)
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ..checks import (
    check_affine,
    check_array,
    check_choice,
    check_count,
    check_flag,
    check_number,
    check_vec3,
)
from ..errors import SceneError
from ..vocabulary import (
    CSG_OPERATIONS,
    SHAPE_BOX,
    SHAPE_CONE,
    SHAPE_CSG,
    SHAPE_CYLINDER,
    SHAPE_MESH,
    SHAPE_SPHERE,
    SHAPE_TORUS,
)
from .materials import Material

# Blender's largest Pass Index (objects and materials alike)
MAX_PASS_INDEX = 32767


def _identity() -> np.ndarray:
    return np.eye(4)


@dataclass(eq=False)
class Shape:
    """casts_shadows -- False: light passes the shape as if it were not there (Blender's
    Object > Visibility > Ray Visibility > Shadow). Of a CSG tree only the top node's counts.
    holdout       -- camera rays that meet it see a hole: no colour, alpha 0 (Blender's
                     Object > Visibility > Holdout, and holdout collections); it still casts
                     shadows and shows in mirrors and through glass, as in Cycles
    pass_index    -- its value in the object index pass (Object > Relations > Pass Index)
    texture_space -- (centre, half size), object-space triples: the box Blender's Generated
                     texture coordinates map to [0, 1] (a mesh's Texture Space); None: the
                     shape's own box
    lights_diffuse -- False: its material's emission lights no diffuse surface (Blender's Ray
                     Visibility > Diffuse off), however the material says
    seen_by_camera, seen_in_mirrors, seen_through_glass -- False: camera rays, reflected
                     rays or refracted rays pass through it as if it were not there
                     (Object > Visibility > Ray Visibility > Camera, Glossy, Transmission)
    Of a CSG tree, the top node's holdout, pass_index and visibility hold for all of it."""

    name: str = "Shape"
    material: Material = field(default_factory=Material)
    world_from_object: np.ndarray = field(default_factory=_identity)
    casts_shadows: bool = field(default=True, kw_only=True)
    holdout: bool = field(default=False, kw_only=True)
    pass_index: int = field(default=0, kw_only=True)
    texture_space: tuple | None = field(default=None, kw_only=True)
    lights_diffuse: bool = field(default=True, kw_only=True)
    seen_by_camera: bool = field(default=True, kw_only=True)
    seen_in_mirrors: bool = field(default=True, kw_only=True)
    seen_through_glass: bool = field(default=True, kw_only=True)

    kind_name = "shape"  # how messages name the kind
    kernel_kind = -1  # its code in the shape table (core.kernels.shapes)

    @property
    def owner(self) -> str:
        return f"{self.kind_name} '{self.name}'"

    def validate(self, checked: set | None = None) -> None:
        """Raise SceneError on bad fields. `checked` holds the ids of transforms and
        materials already validated (by `Scene.validate`, which checks all transforms at
        once and each shared material once)."""
        checked = checked if checked is not None else set()
        if id(self.world_from_object) not in checked:
            check_affine(self.owner, "world_from_object", self.world_from_object)
        check_flag(self.owner, "casts_shadows", self.casts_shadows)
        check_flag(self.owner, "holdout", self.holdout)
        for name in ("seen_by_camera", "seen_in_mirrors", "seen_through_glass", "lights_diffuse"):
            check_flag(self.owner, name, getattr(self, name))
        if self.texture_space is not None:
            if not isinstance(self.texture_space, tuple | list) or len(self.texture_space) != 2:
                raise SceneError(self.owner, "texture_space", "give (centre, half size)")
            check_vec3(self.owner, "texture_space centre", self.texture_space[0])
            check_vec3(self.owner, "texture_space half size", self.texture_space[1])
        check_count(self.owner, "pass_index", self.pass_index, high=MAX_PASS_INDEX)
        if not isinstance(self.material, Material):
            raise SceneError(
                self.owner, "material", f"got {type(self.material).__name__}; need a Material"
            )
        if id(self.material) not in checked:
            self.material.validate(self.owner)
            checked.add(id(self.material))


@dataclass(eq=False)
class Sphere(Shape):
    kind_name = "sphere"
    kernel_kind = SHAPE_SPHERE


@dataclass(eq=False)
class Box(Shape):
    kind_name = "box"
    kernel_kind = SHAPE_BOX


@dataclass(eq=False)
class Cylinder(Shape):
    kind_name = "cylinder"
    kernel_kind = SHAPE_CYLINDER


@dataclass(eq=False)
class Cone(Shape):
    kind_name = "cone"
    kernel_kind = SHAPE_CONE


@dataclass(eq=False)
class Torus(Shape):
    major_radius: float = 1.0
    minor_radius: float = 0.25

    kind_name = "torus"
    kernel_kind = SHAPE_TORUS

    def validate(self, checked: set | None = None) -> None:
        super().validate(checked)
        check_number(self.owner, "major_radius", self.major_radius, low=0.0, low_open=True)
        check_number(self.owner, "minor_radius", self.minor_radius, low=0.0, low_open=True)


@dataclass(eq=False)
class TriangleMesh:
    """Triangle geometry in object space, shareable between `Mesh` instances.

    vertices        -- (v, 3) positions
    triangles       -- (t, 3) vertex indices, counter-clockwise seen from outside
    smooth          -- whether faces are smooth shaded: one bool for all, or (t,) per face;
                       smooth faces interpolate normals across the face, flat faces use the
                       face's own normal
    vertex_normals  -- (v, 3) normals per vertex, or None
    corner_normals  -- (t, 3, 3) normals per triangle corner (Blender's split normals), or None;
                       with neither, smooth faces use area-weighted vertex normals
    vertex_uvs      -- (v, 2) texture coordinates per vertex, or None
    corner_uvs      -- (t, 3, 2) texture coordinates per triangle corner, or None
    corner_colors   -- {name: (t, 3, 4) linear RGBA per triangle corner}: the colour
                       attributes a shader's Color Attribute and Attribute nodes read by
                       name (Blender's vertex and face-corner colours), or None
    default_color   -- the name of the one read where the node names none (Blender's
                       render colour), "" for none
    corner_tangents -- (t, 3, 4) per triangle corner: the object-space tangent of the UV map
                       (xyz) and the bitangent's sign (w), as Blender's MikkTSpace gives
                       them, for tangent-space normal maps (interpolated over the triangle,
                       as Cycles does); None: each triangle's own UV gradient is used
    """

    vertices: np.ndarray
    triangles: np.ndarray
    smooth: bool | np.ndarray = False
    vertex_normals: np.ndarray | None = None
    corner_normals: np.ndarray | None = None
    vertex_uvs: np.ndarray | None = None
    corner_uvs: np.ndarray | None = None
    name: str = "Mesh"
    corner_colors: dict | None = None
    default_color: str = ""
    corner_tangents: np.ndarray | None = None

    def open_edge_count(self) -> int:
        """How many directed edges have no opposite edge (b, a) used exactly once: 0 for
        a closed, consistently oriented mesh (what a CSG operand must be)."""
        triangles = np.asarray(self.triangles, np.int64)
        if len(triangles) == 0:
            return 0
        edges = triangles[:, [0, 1, 1, 2, 2, 0]].reshape(-1, 2)
        base = int(triangles.max()) + 1
        keys = edges[:, 0] * base + edges[:, 1]
        unique, counts = np.unique(keys, return_counts=True)
        opposite = edges[:, 1] * base + edges[:, 0]
        position = np.searchsorted(unique, opposite).clip(0, len(unique) - 1)
        matched = (unique[position] == opposite) & (counts[position] == 1)
        repeated = counts[np.searchsorted(unique, keys)] > 1
        return int(np.count_nonzero(~matched | repeated))

    def validate(self, owner: str) -> None:
        vertices = check_array(owner, "vertices", self.vertices, 3, "float")
        triangles = check_array(owner, "triangles", self.triangles, 3, "int")
        if triangles.size and (triangles.min() < 0 or triangles.max() >= len(vertices)):
            bad = int(np.argwhere((triangles < 0) | (triangles >= len(vertices)))[0][0])
            raise SceneError(
                owner,
                "triangles",
                f"triangle {bad} is {triangles[bad].tolist()}; vertex indices must lie in "
                f"0..{len(vertices) - 1}",
            )
        t, v = len(triangles), len(vertices)
        smooth = np.asarray(self.smooth)
        if smooth.shape not in ((), (t,)):
            raise SceneError(owner, "smooth", f"got shape {smooth.shape}; use one bool or ({t},)")
        for name, value, shape in (
            ("vertex_normals", self.vertex_normals, (v, 3)),
            ("corner_normals", self.corner_normals, (t, 3, 3)),
            ("vertex_uvs", self.vertex_uvs, (v, 2)),
            ("corner_uvs", self.corner_uvs, (t, 3, 2)),
            ("corner_tangents", self.corner_tangents, (t, 3, 4)),
        ):
            if value is None:
                continue
            a = np.asarray(value)
            if a.shape != shape or a.dtype.kind not in "iuf":
                raise SceneError(owner, name, f"got shape {a.shape}; use {shape} numbers")
            if not np.all(np.isfinite(a)):
                raise SceneError(owner, name, "contains NaN or infinity; use finite numbers")
        self._validate_colors(owner, t)

    def _validate_colors(self, owner: str, t: int) -> None:
        colors = self.corner_colors or {}
        if not isinstance(colors, dict):
            raise SceneError(owner, "corner_colors", "use a dict of name: (t, 3, 4) RGBA")
        for name, value in colors.items():
            a = np.asarray(value)
            if not isinstance(name, str) or a.shape != (t, 3, 4) or a.dtype.kind not in "iuf":
                raise SceneError(owner, f"corner_colors[{name!r}]",
                                 f"got shape {a.shape}; use ({t}, 3, 4) numbers")  # fmt: skip
            if not np.all(np.isfinite(a)):
                raise SceneError(owner, f"corner_colors[{name!r}]",
                                 "contains NaN or infinity; use finite numbers")  # fmt: skip
        if self.default_color and self.default_color not in colors:
            named = ", ".join(map(repr, colors)) or "none"
            raise SceneError(owner, "default_color", f"got {self.default_color!r}; name one of "
                             f"corner_colors ({named}) or ''")  # fmt: skip


@dataclass(eq=False)
class Mesh(Shape):
    mesh: TriangleMesh | None = None

    kind_name = "mesh"
    kernel_kind = SHAPE_MESH

    def validate(self, checked: set | None = None) -> None:
        super().validate(checked)
        if not isinstance(self.mesh, TriangleMesh):
            raise SceneError(
                self.owner, "mesh", f"got {type(self.mesh).__name__}; need a TriangleMesh"
            )
        if checked is None or id(self.mesh) not in checked:
            self.mesh.validate(self.owner)
            if checked is not None:
                checked.add(id(self.mesh))


ANALYTIC_SHAPES = (Sphere, Box, Cylinder, Cone, Torus)


@dataclass(eq=False)
class Csg(Shape):
    """A constructive solid: `left` combined with `right` by `operation`, one of "union",
    "intersection" or "difference" (left minus right).

    Operands are any shapes, other `Csg` nodes included, to any depth. An operand's
    `world_from_object` places it in this node's object space, so the node's own
    `world_from_object` moves the whole solid. One operand may serve several nodes (one
    cutter for many objects). Each surface keeps its operand's material; a subtracted
    operand's surface faces into the hole. The node's own `material` is not used. A mesh
    operand must be closed and consistently oriented (`TriangleMesh.is_closed`).
    """

    operation: str = "union"
    left: Shape | None = None
    right: Shape | None = None

    kind_name = "CSG"
    kernel_kind = SHAPE_CSG

    def validate(self, checked: set | None = None) -> None:
        checked = checked if checked is not None else set()
        self._validate_tree(checked, path=[])

    def _validate_tree(self, checked: set, path: list) -> None:
        if id(self) in checked:
            return
        super().validate(checked)
        check_choice(self.owner, "operation", self.operation, tuple(CSG_OPERATIONS))
        path = [*path, self]
        for field_name in ("left", "right"):
            operand = getattr(self, field_name)
            if not isinstance(operand, Shape) or type(operand) is Shape:
                raise SceneError(
                    self.owner, field_name, f"got {operand!r}; need a shape or a Csg node"
                )
            if any(operand is node for node in path):
                cycle = " -> ".join(node.owner for node in [*path, operand])
                raise SceneError(
                    self.owner,
                    field_name,
                    f"the tree contains itself ({cycle}); a CSG tree cannot have a cycle",
                )
            if isinstance(operand, Csg):
                operand._validate_tree(checked, path)
            else:
                operand.validate(checked)
                if isinstance(operand, Mesh):
                    _check_closed(operand, self.owner, field_name)
        checked.add(id(self))


def _check_closed(operand: Mesh, owner: str, field_name: str) -> None:
    open_edges = operand.mesh.open_edge_count()
    if open_edges:
        raise SceneError(
            owner,
            field_name,
            f"{operand.owner} is not a closed solid: {open_edges} of its edges lack a "
            "matching opposite edge; a CSG operand mesh must be closed and consistently "
            "oriented (every edge shared by two faces, in opposite directions)",
        )
