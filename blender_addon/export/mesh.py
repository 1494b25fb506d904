"""Blender meshes into `core.TriangleMesh`, through `foreach_get` into numpy (no Python loop
over triangles), with per-face smooth flags, Blender's corner (split) normals, the active UV
map and the colour attributes, and its MikkTSpace tangents where a material has a
tangent-space normal map. Each distinct evaluated mesh is converted once per render
and shared by every object instance that uses it, and `MeshCache` keeps it from frame to
frame while it does not change, so an animation re-exports only what moved."""

from __future__ import annotations

import numpy as np

from .. import core
from ..compat import auto_smooth, prepare_corner_normals


class MeshCache:
    """Converted meshes kept between renders (frames of an animation), keyed by the caller,
    and reused while everything the export reads is unchanged: vertex positions, face
    count and smooth flags, sharp edges, UVs and (before Blender 4.1) Auto Smooth, a
    fraction of the export's cost. Meshes with custom normals are always converted afresh."""

    def __init__(self):
        self._entries: dict = {}
        self.conversions = 0  # meshes read from Blender, not reused: what tests count

    def get(self, key, mesh, name: str):
        """(whole `TriangleMesh`, its parts by material slot)."""
        if mesh.has_custom_normals:
            self.conversions += 1
            return _converted(mesh, name)
        fingerprint = _fingerprint(mesh)
        cached = self._entries.get(key)
        if cached is not None and cached[0] == fingerprint:
            return cached[1]
        converted = _converted(mesh, name)
        self.conversions += 1
        self._entries[key] = (fingerprint, converted)
        return converted

    def keep_only(self, keys) -> None:
        """Forget meshes no longer in the scene."""
        self._entries = {k: v for k, v in self._entries.items() if k in keys}


def _converted(mesh, name):
    whole, material_index = convert(mesh, name)
    return whole, by_material(whole, material_index)


def _fingerprint(mesh) -> tuple:
    parts = []
    for collection, attribute, dtype, width in (
        (mesh.vertices, "co", np.float32, 3),
        (mesh.polygons, "use_smooth", bool, 1),
        (mesh.polygons, "loop_total", np.int32, 1),
        (mesh.polygons, "material_index", np.int32, 1),
        (mesh.edges, "use_edge_sharp", bool, 1),
        (mesh.loops, "vertex_index", np.int32, 1),
    ):
        values = np.empty(len(collection) * width, dtype)
        collection.foreach_get(attribute, values)
        parts.append(hash(values.tobytes()))
    uv_layer = mesh.uv_layers.active
    if uv_layer is not None:
        uvs = np.empty(len(mesh.loops) * 2, np.float32)
        uv_layer.data.foreach_get("uv", uvs)
        parts.append(hash(uvs.tobytes()))
    for attribute in getattr(mesh, "color_attributes", ()):
        values = np.empty(len(attribute.data) * 4, np.float32)
        attribute.data.foreach_get("color", values)
        parts.append((attribute.name, attribute.domain, hash(values.tobytes())))
    return (*parts, *auto_smooth(mesh), wants_tangents(mesh))


def triangle_mesh(mesh, name: str) -> core.TriangleMesh:
    """The triangles of a Blender mesh (object space), whatever their materials."""
    return convert(mesh, name)[0]


def convert(mesh, name: str):
    """(the mesh's triangles as one `TriangleMesh`, each triangle's material slot)."""
    mesh.calc_loop_triangles()
    prepare_corner_normals(mesh)
    triangles_blender = mesh.loop_triangles
    count = len(triangles_blender)
    vertices = np.empty(len(mesh.vertices) * 3, np.float32)
    mesh.vertices.foreach_get("co", vertices)
    triangles = np.empty(count * 3, np.int32)
    triangles_blender.foreach_get("vertices", triangles)
    smooth = np.empty(count, bool)
    triangles_blender.foreach_get("use_smooth", smooth)
    corner_normals = None
    if smooth.any():
        corner_normals = np.empty(count * 9, np.float32)
        triangles_blender.foreach_get("split_normals", corner_normals)
        corner_normals = corner_normals.reshape(count, 3, 3)
    corner_uvs = None
    uv_layer = mesh.uv_layers.active
    if uv_layer is not None and count:
        loops = np.empty(count * 3, np.int32)
        triangles_blender.foreach_get("loops", loops)
        uvs = np.empty(len(mesh.loops) * 2, np.float32)
        uv_layer.data.foreach_get("uv", uvs)
        corner_uvs = uvs.reshape(-1, 2)[loops].reshape(count, 3, 2)
    material_index = np.empty(count, np.int32)
    triangles_blender.foreach_get("material_index", material_index)
    corner_colors, default_color = _colour_attributes(mesh, triangles_blender, count)
    corner_tangents = None
    if corner_uvs is not None and wants_tangents(mesh):
        corner_tangents = _tangents(mesh, uv_layer.name, loops, count)
    return core.TriangleMesh(
        vertices=vertices.reshape(-1, 3),
        triangles=triangles.reshape(-1, 3),
        smooth=smooth,
        corner_normals=corner_normals,
        corner_uvs=corner_uvs,
        name=name,
        corner_colors=corner_colors,
        default_color=default_color,
        corner_tangents=corner_tangents,
    ), material_index


def wants_tangents(mesh) -> bool:
    """Whether a material of the mesh has a tangent-space Normal Map (at the top of its
    tree or in a node group): then its MikkTSpace tangents are exported (`_tangents`)."""
    seen = set()

    def has_map(tree) -> bool:
        if tree is None or tree.as_pointer() in seen:
            return False
        seen.add(tree.as_pointer())
        for node in tree.nodes:
            if node.type == "NORMAL_MAP" and node.space == "TANGENT":
                return True
            if node.type == "GROUP" and has_map(node.node_tree):
                return True
        return False

    return any(m is not None and m.use_nodes and has_map(m.node_tree) for m in mesh.materials)


def _tangents(mesh, uv_map: str, loops, count: int):
    """(t, 3, 4) per triangle corner: the UV map's MikkTSpace tangent (object space) and
    bitangent sign, as Blender computes them for Cycles; None where Blender cannot (a face
    of more than four corners: the kernels then use each triangle's UV gradient)."""
    try:
        mesh.calc_tangents(uvmap=uv_map)
    except RuntimeError:
        return None
    tangent = np.empty(len(mesh.loops) * 3, np.float32)
    mesh.loops.foreach_get("tangent", tangent)
    sign = np.empty(len(mesh.loops), np.float32)
    mesh.loops.foreach_get("bitangent_sign", sign)
    mesh.free_tangents()
    corner = np.concatenate([tangent.reshape(-1, 3), sign[:, None]], axis=1)
    return corner[loops].reshape(count, 3, 4)


def _colour_attributes(mesh, triangles, count: int):
    """({name: (t, 3, 4) linear RGBA per triangle corner} of the mesh's colour attributes,
    vertex or face-corner, byte or float alike (Blender gives both as linear floats); the
    name of its render colour, which a Color Attribute node naming none reads, or "")."""
    attributes = getattr(mesh, "color_attributes", None)
    if attributes is None or not len(attributes) or not count:
        return None, ""
    loops = np.empty(count * 3, np.int32)
    triangles.foreach_get("loops", loops)
    vertex_of_loop = np.empty(len(mesh.loops), np.int32)
    mesh.loops.foreach_get("vertex_index", vertex_of_loop)
    colours = {}
    for attribute in attributes:
        if attribute.domain not in ("CORNER", "POINT"):
            continue
        values = np.empty(len(attribute.data) * 4, np.float32)
        attribute.data.foreach_get("color", values)
        at = loops if attribute.domain == "CORNER" else vertex_of_loop[loops]
        colours[attribute.name] = values.reshape(-1, 4)[at].reshape(count, 3, 4)
    render = getattr(attributes, "render_color_index", -1)
    default = attributes[render].name if 0 <= render < len(attributes) else ""
    return colours, default if default in colours else ""


def by_material(whole: core.TriangleMesh, material_index) -> dict[int, core.TriangleMesh]:
    """The mesh split by material slot (core gives a shape one material): {slot: part}.
    The parts share the vertex array; a mesh with one slot is its own single part."""
    slots = np.unique(material_index)
    if len(slots) <= 1:
        return {int(slots[0]) if len(slots) else 0: whole}
    parts = {}
    for slot in slots:
        rows = material_index == slot

        def pick(table, rows=rows):
            return None if table is None else table[rows]

        parts[int(slot)] = core.TriangleMesh(
            vertices=whole.vertices,
            triangles=whole.triangles[rows],
            smooth=np.asarray(whole.smooth)[rows],
            corner_normals=pick(whole.corner_normals),
            corner_uvs=pick(whole.corner_uvs),
            name=f"{whole.name}[{slot}]",
            corner_colors=None if whole.corner_colors is None
            else {key: table[rows] for key, table in whole.corner_colors.items()},
            default_color=whole.default_color,
            corner_tangents=pick(whole.corner_tangents),
        )  # fmt: skip
    return parts
