"""One gr.render call: the scene under its node as it stood, and how to render it."""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ..errors import SceneError
from ..model import Camera, Material, RenderSettings, Scene
from .graph import CsgNode, GeometryNode, Node, vec3
from .render_options import RenderOptions
from .sandbox import ArgumentError

# The most shapes one gr.render call may draw. A node under several parents is drawn once per
# path to it, and a few levels of shared nodes make billions of paths: counted first, they
# are refused before any is made (each drawn shape costs about a kilobyte here)
MAX_SHAPES = 1_000_000

# A shape with no material renders in this, with a warning (A4 would have crashed)
UNSET_MATERIAL = Material(diffuse=(0.7, 0.7, 0.7), specular=(0.0, 0.0, 0.0), name="(none set)")


@dataclass
class RenderCall:
    """The arguments of gr.render. Without the report's extra arguments: no recursion
    limit given (the core's default), supersampling off, one shadow ray, no depth of field,
    as the report's program defaulted."""

    root: Node
    output: Path
    width: int
    height: int
    eye: tuple
    view: tuple
    up: tuple
    fovy: float
    ambient: tuple
    lights: list
    max_recursion: int | None = None
    supersampling: bool = False
    shadow_rays: int = 1
    focal_length: float | None = None
    aperture_radius: float = 0.0
    options: RenderOptions = field(default_factory=RenderOptions)  # Whitted's extension
    scene: Scene | None = None
    settings: RenderSettings | None = None
    warnings: list[str] = field(default_factory=list)

    def build(self) -> None:
        """Make `scene` and `settings` from the nodes as they are now, and check them."""
        drawn = shape_count(self.root)
        if drawn > MAX_SHAPES:
            raise ArgumentError(
                f"{self.root} draws {drawn:,} shapes (a node under several parents is drawn "
                f"once per path to it); at most {MAX_SHAPES:,} are rendered"
            )
        shapes: list = []
        unset: list[str] = []
        _collect(self.root, np.eye(4), shapes, unset)
        if unset:
            names = ", ".join(f"'{name}'" for name in sorted(set(unset))[:5])
            self.warnings.append(
                f"{len(set(unset))} shape(s) have no material ({names}): they render grey"
            )
        camera = Camera(
            eye=self.eye,
            view=self.view,
            up=self.up,
            fovy=self.fovy,
            name="gr.render",
            aperture_radius=self.aperture_radius if self.focal_length else 0.0,
            focal_distance=self.focal_length or 1.0,
        )
        # The ambient term lights every surface and is also the background, as the world
        # colour is in Blender, so an imported script renders the same there
        self.scene = Scene(camera, shapes, [light.core for light in self.lights],
                           self.ambient, self.ambient)  # fmt: skip
        self.settings = RenderSettings(
            width=self.width,
            height=self.height,
            pixel_samples=3 if self.supersampling else 1,
            pixel_sampling="grid",
            shadow_samples=self.shadow_rays,
            **self.options.settings(),
        )
        if self.max_recursion is not None:
            self.settings.max_depth = self.max_recursion
        try:
            self.scene.validate()
            self.settings.validate()
        except SceneError as error:
            # The camera's fields are gr.render's own arguments (eye, view, up, fovy)
            camera = error.owner == f"camera '{camera.name}'"
            raise ArgumentError(
                f"{error.field}: {error.problem}" if camera else str(error)
            ) from None

    def summary(self) -> str:
        """The report's print-out of the render arguments."""
        lines = [
            "Calling A4_Render(",
            f"  SceneNode:[name:{self.root.name}, id:{self.root.id}]",
            f"  Image(width:{self.width}, height:{self.height})",
            f"  eye:  {vec3(self.eye)}",
            f"  view: {vec3(self.view)}",
            f"  up:   {vec3(self.up)}",
            f"  fovy: {self.fovy:g}",
            f"  ambient: {vec3(self.ambient)}",
            "  lights{",
            *(f"    {light}" for light in self.lights),
            "  }",
            ")",
            "",
            f"Max recursion level: {self.settings.max_depth}",
            f"Supersampling is turned {'on' if self.supersampling else 'off'}",
            f"Soft shadow Ray number: {self.shadow_rays}",
        ]
        if self.focal_length:
            lines += [
                "Depth of field is turned on",
                f"Focal Length: {self.focal_length:g}",
                f"Aperture Radius: {self.aperture_radius:g}",
            ]
        else:
            lines.append("Depth of field is turned off")
        return "\n".join(lines + self.options.summary())


def _collect(node: Node, parent: np.ndarray, shapes: list, unset: list) -> None:
    """Every shape under `node` (placed by `parent`), once per path to it: a node under two
    parents is drawn twice, as A4's instancing does. In the order of a depth-first walk,
    kept on a list of its own rather than Python's stack, so that no depth of nesting runs
    out of it."""
    pending = [(node, parent)]
    while pending:
        node, parent = pending.pop()
        if isinstance(node, GeometryNode):
            material = node.material.core if node.material is not None else None
            if material is None:
                unset += _unset_names(node)
            shape = node.core_shape(material or UNSET_MATERIAL)
            shape.world_from_object = parent @ shape.world_from_object
            shapes.append(shape)
        placed = parent @ node.matrix
        pending += [(child, placed) for child in reversed(node.children)]


def shape_count(root: Node) -> int:
    """How many shapes `_collect` would make under `root`, in time linear in the nodes: each
    node's count once, from its children's (a walk that finishes children first)."""
    counts: dict[int, int] = {}
    pending = [(root, False)]
    while pending:
        node, children_done = pending.pop()
        if id(node) in counts:
            continue
        if children_done:
            own = 1 if isinstance(node, GeometryNode) else 0
            counts[id(node)] = own + sum(counts[id(child)] for child in node.children)
        else:
            pending.append((node, True))
            pending += [(c, False) for c in node.children if id(c) not in counts]
    return counts[id(root)]


def _unset_names(node: GeometryNode) -> list[str]:
    """The shapes that will render without a material: a CSG node's operands inherit its."""
    if not isinstance(node, CsgNode):
        return [node.name]
    return [
        name
        for operand in (node.left, node.right)
        if operand.material is None
        for name in _unset_names(operand)
    ]
