"""The scene graph a CS488 script builds: nodes with transforms, shapes, CSG, materials, lights.

Conventions are the CS488 framework's and the report's:
- a node's `translate`, `rotate` and `scale` apply after those before them, in the parent's
  frame (each multiplies the node's matrix from the left), and a node's matrix places its
  children and its own shape in its parent's frame;
- a node may be the child of several parents (A4's instancing); a cycle is an error;
- shapes are y-up: the report's cylinder is centred on the origin, radius 1, y in [-1, 1];
  its cone has the apex at the origin and the base of radius 1 at y = 2 (x^2 + z^2 =
  (y / 2)^2, as the report solves it); the torus turns about the z axis (major radius 5,
  minor 2); gr.cube is the unit cube [0, 1]^3, as in A4.

`object_matrix` maps each of the core's canonical z-up forms onto these, so every shape stays
exact; `GeometryNode.core_shape` gives the core shape in the node's frame.
"""

from __future__ import annotations

import numpy as np

from ..model import Box, Cone, Csg, Cylinder, Material, Mesh, Sphere, Torus, TriangleMesh
from ..vocabulary import CSG_OPERATIONS
from .sandbox import ArgumentError, ScriptObject

AXES = {"x": 0, "y": 1, "z": 2}
# The A4 language's names for the CSG operations (core.vocabulary's), in the manual's order
A4_OPERATIONS = {"union": "union", "intersection": "intersection", "diff": "difference"}
assert set(A4_OPERATIONS.values()) == set(CSG_OPERATIONS)


def translation(offset) -> np.ndarray:
    m = np.eye(4)
    m[:3, 3] = offset
    return m


def scaling(factors) -> np.ndarray:
    return np.diag([*np.asarray(factors, float), 1.0])


def rotation(axis: str, degrees: float) -> np.ndarray:
    """A turn of `degrees` about a coordinate axis, counter-clockwise looking down the axis.
    Quarter turns are exact (no 6e-17 where a 0 belongs)."""
    quarter, rest = divmod(float(degrees), 90.0)
    if rest == 0.0:
        c, s = ((1.0, 0.0), (0.0, 1.0), (-1.0, 0.0), (0.0, -1.0))[int(quarter) % 4]
    else:
        c, s = np.cos(np.radians(degrees)), np.sin(np.radians(degrees))
    i = AXES[axis]
    j, k = (i + 1) % 3, (i + 2) % 3
    m = np.eye(4)
    m[j, j], m[j, k], m[k, j], m[k, k] = c, -s, s, c
    return m


# Object z onto y (a turn of -90 degrees about x), for shapes whose axis is the report's y
Z_TO_Y = rotation("x", -90)
# Object z onto -y (+90 degrees about x): the core cone's apex (z = 1) to the bottom; also
# what stands a y-up scene upright in Blender's z-up world
Z_TO_MINUS_Y = rotation("x", 90)


def object_matrix(kind: str, centre=(0.0, 0.0, 0.0), size: float = 1.0, height: float = 2.0):
    """The matrix placing the core's canonical `kind` as the report's shape with that centre
    (corner for a box), size (radius, or edge for a box) and height."""
    at = translation(centre)
    if kind == "sphere":
        return at @ Z_TO_Y @ scaling((size, size, size))
    if kind == "cube":
        half = size / 2.0
        return at @ translation((half, half, half)) @ scaling((half, half, half))
    if kind == "cylinder":
        return at @ Z_TO_Y @ scaling((size, size, height / 2.0))
    if kind == "cone":
        up = translation((0.0, height / 2.0, 0.0))
        return at @ up @ Z_TO_MINUS_Y @ scaling((size, size, height / 2.0))
    return at  # torus (already about z) and mesh


class Node(ScriptObject):
    """gr.node: a transform and children."""

    lua_kind = "node"
    lua_methods = ("add_child", "set_material", "set_texture", "translate", "rotate", "scale")

    def __init__(self, name: str):
        self.name = name
        self.id = 0  # the creation count within the script, as A4 numbers nodes
        self.matrix = np.eye(4)
        self.children: list[Node] = []
        self.parents: list[Node] = []
        self.used_by_csg: Node | None = None

    def __str__(self) -> str:
        return f"{self.kind_name} '{self.name}'"

    @property
    def kind_name(self) -> str:
        return self.lua_kind

    def add_child(self, child) -> None:
        if not isinstance(child, Node):
            raise ArgumentError(f"{self}: the child must be a node; got {describe(child)}")
        if self.used_by_csg is not None:
            raise ArgumentError(
                f"{self} is an operand of {self.used_by_csg}: a CSG operand is one shape, "
                "without children"
            )
        if any(c is child for c in self.children):
            raise ArgumentError(f"{child} is already a child of {self}; a node is added once")
        if child.used_by_csg is not None:
            raise ArgumentError(
                f"{child} is an operand of {child.used_by_csg}; add the CSG node instead "
                "(an operand belongs to its CSG node only)"
            )
        path = _path_up(self, child)
        if path is not None:
            chain = " -> ".join(str(n) for n in [child, *path])
            raise ArgumentError(f"adding {child} under {self} makes a cycle ({chain})")
        self.children.append(child)
        child.parents.append(self)

    def set_material(self, material) -> None:
        raise ArgumentError(f"{self} has no shape to colour; set materials on shape nodes")

    def set_texture(self, texture) -> None:
        raise ArgumentError(f"{self} has no shape to texture; set textures on shape nodes")

    def translate(self, *args) -> None:
        self.matrix = translation(_three_numbers(args)) @ self.matrix

    def scale(self, *args) -> None:
        factors = _three_numbers(args)
        if 0.0 in factors:
            raise ArgumentError(f"{self}: scale by {factors}: a factor of 0 flattens the node")
        self.matrix = scaling(factors) @ self.matrix

    def rotate(self, *args) -> None:
        if len(args) != 2:
            raise ArgumentError(f"takes 2 arguments (axis, degrees); got {len(args)}")
        axis, degrees = args
        if not isinstance(axis, str) or axis.lower() not in AXES:
            raise ArgumentError(f"{self}: axis must be 'x', 'y' or 'z'; got {describe(axis)}")
        check_number(degrees, "degrees")
        self.matrix = rotation(axis.lower(), degrees) @ self.matrix


class GeometryNode(Node):
    """A node with a shape (gr.sphere, gr.nh_box, gr.mesh...), whose material and texture
    can be set; its children are placed as a plain node's are."""

    def __init__(self, name, kind, shape_matrix, mesh: TriangleMesh | None = None, radii=None):
        super().__init__(name)
        self.kind = kind
        self.shape_matrix = shape_matrix
        self.mesh = mesh
        self.radii = radii  # torus (major, minor)
        self.material: MaterialSpec | None = None

    @property
    def kind_name(self) -> str:
        return "CSG node" if self.kind == "csg" else self.kind

    def set_material(self, material) -> None:
        self.material = _checked_material(self, material, textured=False)

    def set_texture(self, texture) -> None:
        self.material = _checked_material(self, texture, textured=True)

    def core_shape(self, material: Material):
        """The core shape, placed in this node's frame."""
        kinds = {"sphere": Sphere, "cube": Box, "cylinder": Cylinder, "cone": Cone}
        if self.kind == "torus":
            major, minor = self.radii
            shape = Torus(self.name, material, major_radius=major, minor_radius=minor)
        elif self.kind == "mesh":
            shape = Mesh(self.name, material, mesh=self.mesh)
        else:
            shape = kinds[self.kind](self.name, material)
        shape.world_from_object = self.matrix @ self.shape_matrix
        return shape


class CsgNode(GeometryNode):
    """gr.csg: two shape or CSG nodes combined; a material set on it colours the operand
    surfaces that have none of their own."""

    lua_kind = "CSG node"

    def __init__(self, name, left: Node, right: Node, operation: str):
        super().__init__(name, "csg", np.eye(4))
        self.left, self.right, self.operation = left, right, operation
        left.used_by_csg = right.used_by_csg = self
        self.operands = operand_count(left) + operand_count(right)

    def core_shape(self, material: Material):
        operands = []
        for operand in (self.left, self.right):
            own = operand.material.core if operand.material is not None else material
            operands.append(operand.core_shape(own))
        return Csg(
            self.name,
            material,
            self.matrix,
            operation=A4_OPERATIONS[self.operation],
            left=operands[0],
            right=operands[1],
        )


class MaterialSpec(ScriptObject):
    """gr.material or gr.texture: the core material it becomes, shared by every user."""

    lua_kind = "material"

    def __init__(self, core: Material, textured: bool, call_id: int):
        self.core = core
        self.textured = textured
        self.call_id = call_id

    def __str__(self) -> str:
        return f"{'texture' if self.textured else 'material'} {self.call_id}"


class LightSpec(ScriptObject):
    """gr.light: the core light, and the report's fields for the summary."""

    lua_kind = "light"

    def __init__(self, core, colour, position, falloff, size=None):
        self.core = core
        self.colour, self.position, self.falloff, self.size = colour, position, falloff, size

    def __str__(self) -> str:
        text = f"L[{vec3(self.colour)}, {vec3(self.position)}, " + ", ".join(
            f"{c:g}" for c in self.falloff
        )
        if self.size is not None:
            text += f"; width: {self.size[0]:g}, height: {self.size[1]:g}"
        return text + "]"


def _checked_material(node, material, textured: bool):
    method = "set_texture" if textured else "set_material"
    if not isinstance(material, MaterialSpec):
        made_by = "gr.texture" if textured else "gr.material"
        raise ArgumentError(
            f"{node}: {method} takes what {made_by} makes; got {describe(material)}"
        )
    if material.textured != textured:
        right = "set_texture" if material.textured else "set_material"
        raise ArgumentError(f"{node}: {material} goes on with {right}, not {method}")
    return material


def operand_count(node: Node) -> int:
    """The shapes a CSG tree rooted at `node` combines (1 for a shape)."""
    return node.operands if isinstance(node, CsgNode) else 1


def _path_up(node: Node, target: Node) -> list[Node] | None:
    """A chain of parents from `node` up to `target` (target an ancestor of node, or node
    itself), or None. A search over parents that visits each node once: a graph of shared
    children has exponentially many paths, and a deep one would run out of Python's stack."""
    came_from = {id(node): None}
    pending = [node]
    while pending:
        current = pending.pop()
        if current is target:
            chain = [current]
            while came_from[id(chain[-1])] is not None:
                chain.append(came_from[id(chain[-1])])
            return chain[::-1]
        for parent in current.parents:
            if id(parent) not in came_from:
                came_from[id(parent)] = current
                pending.append(parent)
    return None


def _three_numbers(args) -> tuple[float, float, float]:
    if len(args) != 3:
        raise ArgumentError(f"takes 3 arguments (x, y, z); got {len(args)}")
    return tuple(check_number(v, "xyz"[i]) for i, v in enumerate(args))


def check_number(value, what: str) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise ArgumentError(f"{what} must be a number; got {describe(value)}")
    if not np.isfinite(value):
        raise ArgumentError(f"{what} must be a finite number; got {value}")
    return float(value)


def describe(value) -> str:
    """A value as a message names it: `a string 'abc'`, `the number 3`, `nil`..."""
    if value is None:
        return "nil"
    if isinstance(value, bool):
        return f"the boolean {str(value).lower()}"
    if isinstance(value, (int, float)):
        return f"the number {value:g}"
    if isinstance(value, str):
        return f"the string '{value}'"
    if isinstance(value, list):
        return f"a table of {len(value)} value" + ("" if len(value) == 1 else "s")
    if isinstance(value, dict):
        return "a table with named fields"
    if isinstance(value, ScriptObject):
        return str(value)
    return f"a {type(value).__name__}"


def vec3(values) -> str:
    return "vec3(" + ", ".join(f"{v:f}" for v in values) + ")"
