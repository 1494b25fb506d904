"""The `gr` commands of the CS488 A4 language and the report's extensions, with their
argument checks.

Every call is checked as it is made (count, types, ranges, files), so a mistake is reported
at the script line that made it; the report's own program checked nothing. Relative file
names (meshes, textures, the output PNG) are resolved against the script's own folder.
"""

from __future__ import annotations

import errno
import os
from pathlib import Path

import numpy as np

from ..model import AreaLight, Material, PointLight, Texture, TriangleMesh
from ..obj_file import ObjError, read_obj, summed_face_normals
from ..textures import ImageFileError, read_rgb
from ..vocabulary import MAX_OPERANDS
from .graph import (
    A4_OPERATIONS,
    CsgNode,
    GeometryNode,
    LightSpec,
    MaterialSpec,
    Node,
    check_number,
    describe,
    object_matrix,
    operand_count,
)
from .render_call import RenderCall
from .render_options import RenderOptions, script_options
from .sandbox import ArgumentError

MATERIAL_USAGE = "{dr, dg, db}, {sr, sg, sb}, p[, reflectivity[, outer_ior[, inner_ior]]]"
TEXTURE_USAGE = "file, {sr, sg, sb}, p[, reflectivity[, outer_ior[, inner_ior]]]"
RENDER_USAGE = (
    "node, file, width, height, eye, view, up, fovy, ambient, lights[, max_recursion, "
    "supersampling, shadow_rays[, focal_length, aperture_radius]][, options]"
)
# Every gr command, as the A4 language and the report's manual name them
GR_COMMANDS = (
    "node", "joint", "sphere", "cube", "nh_sphere", "nh_box", "mesh", "torus", "nh_torus",
    "cylinder", "nh_cylinder", "cone", "nh_cone", "csg", "material", "texture", "light",
    "render",
)  # fmt: skip


def expect(args, counts: tuple[int, ...], usage: str) -> None:
    """Check the number of arguments: "takes 3 to 6 arguments (usage); got 7"."""
    if len(args) in counts:
        return
    if len(counts) > 2 and counts == tuple(range(counts[0], counts[-1] + 1)):
        allowed = f"{counts[0]} to {counts[-1]}"
    else:
        *rest, last = map(str, counts)
        allowed = f"{', '.join(rest)} or {last}" if rest else last
    noun = "argument" if counts == (1,) else "arguments"
    raise ArgumentError(f"takes {allowed} {noun} ({usage}); got {len(args)}")


def name_of(value, what="name") -> str:
    if not isinstance(value, str):
        raise ArgumentError(f"{what} must be a string; got {describe(value)}")
    return value


def numbers(value, what: str, count: int = 3, low: float | None = None) -> tuple:
    if not isinstance(value, list) or len(value) != count:
        raise ArgumentError(f"{what} must be a table of {count} numbers; got {describe(value)}")
    result = tuple(check_number(v, f"{what} value {i + 1}") for i, v in enumerate(value))
    if low is not None and min(result) < low:
        raise ArgumentError(f"{what} must be at least {low:g} each; got {result}")
    return result


def number(value, what: str, low: float | None = None, above: float | None = None) -> float:
    x = check_number(value, what)
    if low is not None and x < low:
        raise ArgumentError(f"{what} must be at least {low:g}; got {x:g}")
    if above is not None and x <= above:
        raise ArgumentError(f"{what} must be above {above:g}; got {x:g}")
    return x


def whole(value, what: str, low: int) -> int:
    x = check_number(value, what)
    if x != int(x) or x < low:
        raise ArgumentError(f"{what} must be a whole number of at least {low}; got {x:g}")
    return int(x)


class Commands:
    """The `gr` table of one script run: `api()` gives the functions; `renders` collects the
    gr.render calls, each holding the scene as it stood when called."""

    def __init__(self, folder: Path, print_line, anywhere: bool = False,
                 outside_setting: str = "the command line's --allow-outside-files"):  # fmt: skip
        self.folder = Path(folder)
        self.print_line = print_line
        # Files outside the script's folder tree (symbolic links resolved) are refused
        # unless the user allows them: a script from elsewhere reads and writes only its own
        self.anywhere = anywhere
        self.outside_setting = outside_setting
        self.renders: list[RenderCall] = []
        self.meshes: dict[Path, TriangleMesh] = {}
        self.material_count = 0
        self.node_count = 0

    def numbered(self, node: Node) -> Node:
        node.id = self.node_count
        self.node_count += 1
        return node

    def api(self) -> dict:
        def numbering(command):
            def call(*args):
                made = command(*args)
                return self.numbered(made) if isinstance(made, Node) else made

            return call

        return {name: numbering(getattr(self, name)) for name in GR_COMMANDS}

    def file(self, value, what: str) -> Path:
        name = name_of(value, what)
        if "\0" in name:
            raise ArgumentError(f"{what} {name!r} holds a NUL byte, which no file name can")
        path = self.inside(name, f"{what} '{name}'", "reads")
        try:
            found = path.is_file()
            if found:  # a file the script's user may not read is named now, not at render
                with open(path, "rb"):
                    pass
        except OSError as error:
            raise ArgumentError(f"{what} '{name}': {_reason(error)}") from None
        if not found:
            raise ArgumentError(f"{what} '{name}' {_not_a_file(path, what, name)}")
        return path

    def inside(self, name: str, what: str, does: str) -> Path:
        """`name` relative to the script's folder, refused outside its tree."""
        try:
            path = (self.folder / name).resolve()
            folder = self.folder.resolve()
        except (OSError, RuntimeError) as error:  # RuntimeError: Python 3.11's symlink loop
            raise ArgumentError(f"{what}: {_reason(error)}") from None
        if not self.anywhere and not path.is_relative_to(folder):
            raise ArgumentError(
                f"{what} is outside the script's folder ({path}); a script {does} files in its "
                f"own folder and below only ({self.outside_setting} lifts this)"
            )
        return path

    # Nodes
    def node(self, *args):
        expect(args, (1,), "name")
        return Node(name_of(args[0]))

    def joint(self, *args):
        expect(args, (3,), "name, {x_min, x_init, x_max}, {y_min, y_init, y_max}")
        numbers(args[1], "x range {min, init, max}")
        numbers(args[2], "y range {min, init, max}")
        return Node(name_of(args[0]))  # joints are plain nodes here

    def _shape(self, args, kind, usage, **extra):
        expect(args, (1,), usage)
        return GeometryNode(name_of(args[0]), kind, object_matrix(kind), **extra)

    def sphere(self, *args):
        return self._shape(args, "sphere", "name")

    def cube(self, *args):
        return self._shape(args, "cube", "name")

    def cylinder(self, *args):
        return self._shape(args, "cylinder", "name")

    def cone(self, *args):
        return self._shape(args, "cone", "name")

    def torus(self, *args):
        return self._shape(args, "torus", "name", radii=(5.0, 2.0))

    def nh_sphere(self, *args):
        expect(args, (3,), "name, {x, y, z}, radius")
        centre, radius = numbers(args[1], "centre {x, y, z}"), number(args[2], "radius", above=0)
        return GeometryNode(name_of(args[0]), "sphere", object_matrix("sphere", centre, radius))

    def nh_box(self, *args):
        expect(args, (3,), "name, {x, y, z}, size")
        corner, size = numbers(args[1], "corner {x, y, z}"), number(args[2], "size", above=0)
        return GeometryNode(name_of(args[0]), "cube", object_matrix("cube", corner, size))

    def nh_torus(self, *args):
        expect(args, (4,), "name, {x, y, z}, major_radius, minor_radius")
        centre = numbers(args[1], "centre {x, y, z}")
        major = number(args[2], "major radius", above=0)
        minor = number(args[3], "minor radius", above=0)
        matrix = object_matrix("torus", centre)
        return GeometryNode(name_of(args[0]), "torus", matrix, radii=(major, minor))

    def _nh_solid(self, args, kind):
        expect(args, (4,), "name, {x, y, z}, radius, height")
        centre = numbers(args[1], "centre {x, y, z}")
        radius, height = number(args[2], "radius", above=0), number(args[3], "height", above=0)
        matrix = object_matrix(kind, centre, radius, height)
        return GeometryNode(name_of(args[0]), kind, matrix)

    def nh_cylinder(self, *args):
        return self._nh_solid(args, "cylinder")

    def nh_cone(self, *args):
        return self._nh_solid(args, "cone")

    def mesh(self, *args):
        expect(args, (2, 3), "name, 'file.obj'  or  name, {vertices}, {faces}")
        name = name_of(args[0])
        if len(args) == 2:
            path = self.file(args[1], "mesh file")
            if path not in self.meshes:
                try:
                    self.meshes[path] = read_obj(path, name, f"mesh file '{args[1]}'")
                except ObjError as error:
                    raise ArgumentError(str(error)) from None
            mesh = self.meshes[path]
        else:
            mesh = _listed_mesh(args[1], args[2], name)
        return GeometryNode(name, "mesh", object_matrix("mesh"), mesh=mesh)

    def csg(self, *args):
        expect(args, (3,), "node, node, " + " | ".join(map(repr, A4_OPERATIONS)))
        left, right, operation = args
        for which, operand in (("first", left), ("second", right)):
            if not isinstance(operand, GeometryNode):
                raise ArgumentError(
                    f"the {which} operand must be a shape or CSG node; got {describe(operand)}"
                )
            if operand.parents or operand.children:
                raise ArgumentError(
                    f"the {which} operand, {operand}, has a parent or children: build the "
                    "CSG from shapes without parents, then add the CSG node to the scene"
                )
            if operand.used_by_csg is not None:
                raise ArgumentError(f"{operand} is already an operand of {operand.used_by_csg}")
        if left is right:
            raise ArgumentError(f"both operands are {left}; use two different nodes")
        if operation not in A4_OPERATIONS:
            *names, last = map(repr, A4_OPERATIONS)
            raise ArgumentError(
                f"unknown operation {_quoted(operation)}; use {', '.join(names)} or {last}"
            )
        operands = operand_count(left) + operand_count(right)
        if operands > MAX_OPERANDS:
            raise ArgumentError(
                f"this CSG node would hold {operands} shapes; at most {MAX_OPERANDS} fit one "
                "CSG tree (the renderer combines them in one pass)"
            )
        return CsgNode(f"{left.name} {operation} {right.name}", left, right, operation)

    # Materials and lights
    def material(self, *args):
        expect(args, (3, 4, 5, 6), MATERIAL_USAGE)
        diffuse = numbers(args[0], "diffuse {dr, dg, db}", low=0)
        return self._material(args, diffuse, None)

    def texture(self, *args):
        expect(args, (3, 4, 5, 6), TEXTURE_USAGE)
        path = self.file(args[0], "texture file")
        try:  # decoded here as at the render, so a file that cannot be read is named here
            read_rgb(path)
        except ImageFileError as problem:
            raise ArgumentError(f"texture file '{args[0]}' {problem}") from None
        # The report used the file's values as they are, with no sRGB decoding
        return self._material(args, (1.0, 1.0, 1.0), Texture(path=path, srgb=False))

    def _material(self, args, diffuse, texture):
        specular = numbers(args[1], "specular {sr, sg, sb}", low=0)
        shininess = number(args[2], "shininess p", low=0)
        reflectivity = number(args[3], "reflectivity", low=0) if len(args) > 3 else 0.0
        if reflectivity > 1:
            raise ArgumentError(f"reflectivity must be between 0 and 1; got {reflectivity:g}")
        outer = number(args[4], "outer index of refraction", low=0) if len(args) > 4 else 1.0
        inner = number(args[5], "inner index of refraction", low=0) if len(args) > 5 else 1.0
        if outer == inner:
            outer = inner = 1.0  # no refraction: the report's scripts write it `0, 0`
        elif min(outer, inner) == 0:
            raise ArgumentError(
                f"indices of refraction {outer:g} (outer) and {inner:g} (inner): equal indices "
                "(`0, 0` in the report's scripts) mean no refraction; to refract, both must "
                "be above 0"
            )
        self.material_count += 1
        kind = "texture" if texture else "material"
        core = Material(
            diffuse=diffuse,
            specular=specular,
            shininess=shininess,
            name=f"{kind} {self.material_count}",
            reflectivity=reflectivity,
            # Differing indices make a dielectric: all its colour from Fresnel reflection
            # and refraction, as the report's glass
            transparency=1.0 if inner != outer else 0.0,
            outer_ior=outer,
            inner_ior=inner,
            texture=texture,
        )
        return MaterialSpec(core, texture is not None, self.material_count)

    def light(self, *args):
        expect(args, (3, 5), "{x, y, z}, {r, g, b}, {c0, c1, c2}[, width, height]")
        position = numbers(args[0], "position {x, y, z}")
        colour = numbers(args[1], "colour {r, g, b}", low=0)
        falloff = numbers(args[2], "falloff {c0, c1, c2}", low=0)
        if max(falloff) == 0:
            raise ArgumentError("falloff {c0, c1, c2} cannot be all 0; (1, 0, 0) is no falloff")
        if len(args) == 3:
            return LightSpec(PointLight(position, colour, falloff), colour, position, falloff)
        width, height = number(args[3], "width", above=0), number(args[4], "height", above=0)
        # A rectangle in the report's horizontal plane, width along x and height along z;
        # edges x and -z make its normal (their cross product) the script's up, as Blender's
        # area light has it, so an imported script samples the light the same way
        area = AreaLight(position, (width, 0.0, 0.0), (0.0, 0.0, -height), colour, falloff)
        return LightSpec(area, colour, position, falloff, (width, height))

    def render(self, *args):
        expect(args, (10, 11, 13, 14, 15, 16), RENDER_USAGE)
        options = RenderOptions()
        if len(args) in (11, 14, 16):  # Whitted's options table (core.cs488.render_options)
            options = script_options(args[-1])
            args = args[:-1]
        elif len(args) in (13, 15) and isinstance(args[-1], (dict, list)):
            raise ArgumentError(
                f"the options table comes last, after 10, 13 or 15 arguments; got it after "
                f"{len(args) - 1} ({RENDER_USAGE})"
            )
        root = args[0]
        if not isinstance(root, Node):
            raise ArgumentError(f"the node to render must be a node; got {describe(root)}")
        output = name_of(args[1], "file")
        if Path(output).suffix.lower() != ".png":
            raise ArgumentError(f"file '{output}' must name a .png image")
        lights = args[9]
        if not isinstance(lights, list):
            raise ArgumentError(
                f"lights must be a table of gr.light values; got {describe(lights)}"
            )
        for i, light in enumerate(lights):
            if not isinstance(light, LightSpec):
                raise ArgumentError(
                    f"lights[{i + 1}] is {describe(light)}; lights come from gr.light"
                )
        call = RenderCall(
            root=root,
            output=self.inside(output, f"file '{output}'", "writes"),
            width=whole(args[2], "width", 1),
            height=whole(args[3], "height", 1),
            eye=numbers(args[4], "eye {x, y, z}"),
            view=numbers(args[5], "view {x, y, z}"),
            up=numbers(args[6], "up {x, y, z}"),
            fovy=number(args[7], "fovy"),
            ambient=numbers(args[8], "ambient {r, g, b}", low=0),
            lights=list(lights),
            options=options,
        )
        if len(args) >= 13:
            call.max_recursion = whole(args[10], "max recursion level", 0)
            call.supersampling = number(args[11], "supersampling flag", low=0) > 0
            call.shadow_rays = whole(args[12], "soft shadow ray number", 1)
        if len(args) == 15:
            call.focal_length = number(args[13], "focal length", above=0)
            call.aperture_radius = number(args[14], "aperture radius", low=0)
        call.build()  # checks the whole scene now, so its errors name this line
        self.renders.append(call)
        self.print_line(call.summary())


def _not_a_file(path: Path, what: str, name: str) -> str:
    """What is at `path` instead of a file, as the rest of a sentence."""
    if path.is_dir():
        return f"is a folder, not a file (looked for {path})"
    if os.path.lexists(path):
        try:
            os.stat(path)
        except OSError as error:  # a link: to nothing, or a loop (Python 3.13 resolves loops)
            if error.errno != errno.ELOOP:
                return f"not found (looked for {path}: a symbolic link to nothing)"
            raise ArgumentError(f"{what} '{name}': {_reason(error)}") from None
        # read, a pipe or a device would wait or never end
        return f"is not a regular file (a pipe, socket or device: {path})"
    return f"not found (looked for {path})"


def _reason(error: Exception) -> str:
    """Why the system would not give a file, in its words, with what to do where plain."""
    if isinstance(error, RuntimeError) or getattr(error, "errno", None) == errno.ELOOP:
        return "its path is a loop of symbolic links; point the link at a real file"
    hints = {
        errno.ENAMETOOLONG: "its path is too long for the file system; use a shorter one",
        errno.EACCES: "permission denied; make the file readable",
        errno.ENOTDIR: "a part of its path is a file, not a folder",
        errno.EIO: "the disk could not read it",
    }
    number = getattr(error, "errno", None)
    return hints.get(number) or f"cannot read it: {error.strerror or error}"


def _quoted(value) -> str:
    return f"'{value}'" if isinstance(value, str) else describe(value)


def _listed_mesh(vertices, faces, name: str) -> TriangleMesh:
    """A4's older gr.mesh(name, {{x, y, z}, ...}, {{i, j, k, ...}, ...}), 0-based indices."""
    if not isinstance(vertices, list) or not vertices:
        raise ArgumentError(f"vertices must be a table of {{x, y, z}}; got {describe(vertices)}")
    points = np.array([numbers(v, "a vertex {x, y, z}") for v in vertices])
    if not isinstance(faces, list) or not faces:
        raise ArgumentError(f"faces must be a table of index tables; got {describe(faces)}")
    triangles = []
    for face in faces:
        if not isinstance(face, list) or len(face) < 3:
            raise ArgumentError(
                f"a face must be a table of 3 or more indices; got {describe(face)}"
            )
        corners = [whole(i, "a face index", 0) for i in face]
        if max(corners) >= len(points):
            raise ArgumentError(
                f"a face uses vertex {max(corners)}; there are {len(points)} (0-based)"
            )
        triangles += [(corners[0], corners[k], corners[k + 1]) for k in range(1, len(corners) - 1)]
    triangles = np.array(triangles)
    normals = summed_face_normals(points, triangles)  # smooth, as the report's meshes
    return TriangleMesh(points, triangles, smooth=True, vertex_normals=normals, name=name)
