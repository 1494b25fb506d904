"""Blender depsgraph -> core.Scene. The only module that reads Blender scene data.

Mapping of Blender's values onto the report's model:
- camera: eye, view (-Z), up (+Y) from the camera's world matrix; the vertical field of view
  from Blender's own projection matrix, so sensor size, sensor fit and lens all count;
- point light: intensity = colour * power / (4 pi^2). With attenuation (0, 0, 1) a white
  diffuse surface facing the light then has the brightness Cycles gives it: a point light of
  power P has radiant intensity P / (4 pi) W/sr and a Lambertian surface divides by pi;
- material: from the Principled BSDF, or the Whitted material panel (`material_export`);
- world: its colour (Background node colour times strength) is both the ambient term and the
  background.
"""

from __future__ import annotations

import math

import numpy as np

from . import core
from .csg_export import boolean_modifiers, solid
from .material_export import convert_material, find_node
from .mesh_export import MeshCache
from .shape_tags import BY_TAG

WATTS_TO_INTENSITY = 1.0 / (4.0 * math.pi**2)


# Curves, text, surfaces and metaballs are listed too as the mesh instances they evaluate to
GEOMETRY_TYPES = {"MESH"}
# Meshes converted for earlier renders in this Blender session (frames of an animation)
MESH_CACHE = MeshCache()


class Exporter:
    """Collects shapes from object instances: one `TriangleMesh` per distinct mesh, one
    `Material` per Blender material, and the warnings for the user."""

    def __init__(self, depsgraph):
        self.depsgraph = depsgraph
        self.shapes: list = []
        self.warnings: list[str] = []
        self.materials: dict[str, core.Material] = {}
        self.meshes: dict = {}

    def warn(self, text: str) -> None:
        self.warnings.append(text)

    def add_instance(self, obj, matrix: np.ndarray, tags=None) -> None:
        """One object instance (evaluated) placed by `matrix`; `tags` is the object whose
        Whitted settings it has, when not `obj` itself (see `whitted_source`)."""
        original = obj.original
        settings = (tags or obj).whitted
        # Object > Visibility > Ray Visibility > Shadow (Blender 3.0+; older files lack it)
        casts_shadows = bool(getattr(original, "visible_shadow", True))
        if obj.type == "MESH" and boolean_modifiers(original):
            shape = solid(original, self, self.depsgraph)
        elif obj.type == "MESH" and settings.shape != "MESH":
            shape = self.base_shape(obj, settings)
        else:
            for slot, part in self._instance_mesh(obj).items():
                if len(part.triangles):
                    material = self.material(obj, slot)
                    self.shapes.append(
                        core.Mesh(obj.name, material, matrix, mesh=part,
                                  casts_shadows=casts_shadows)
                    )  # fmt: skip
            return
        shape.world_from_object = matrix
        shape.casts_shadows = casts_shadows
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
            self.meshes[key] = MESH_CACHE.get(key, mesh, mesh.name)
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
            self.meshes[key] = MESH_CACHE.get(key, obj.data, obj.data.name)
        return self.meshes[key][1]

    def material(self, obj, slot: int | None = None) -> core.Material:
        """The object's material in `slot`, or its active one."""
        blender_material = obj.active_material
        if slot is not None:
            slots = obj.material_slots
            blender_material = slots[slot].material if 0 <= slot < len(slots) else None
        key = blender_material.name if blender_material is not None else ""
        if key not in self.materials:
            self.materials[key] = convert_material(blender_material)
        return self.materials[key]


def convert(depsgraph) -> tuple[core.Scene, core.RenderSettings, list[str]]:
    """Export the evaluated scene. Returns (scene, settings, warnings); raises SceneError."""
    scene = depsgraph.scene
    settings = render_settings(scene)
    world = world_colour(scene.world)
    exporter = Exporter(depsgraph)
    lights, skipped = [], []
    for instance in depsgraph.object_instances:
        obj = instance.object
        tags = whitted_source(instance)
        matrix = np.array(instance.matrix_world, dtype=float)
        if obj.type in GEOMETRY_TYPES:
            exporter.add_instance(obj, matrix, tags)
        elif obj.type == "LIGHT" and obj.data.type == "POINT":
            lights.append(_point_light(obj, instance.matrix_world))
        elif obj.type == "LIGHT" and obj.data.type == "SUN":
            lights.append(_sun_light(obj, instance.matrix_world))
        elif obj.type == "LIGHT" and obj.data.type == "AREA":
            light = _area_light(obj, instance.matrix_world)
            if light is None:
                skipped.append(obj.name)
            else:
                lights.append(light)
        elif obj.type == "LIGHT":
            skipped.append(obj.name)
        elif obj.type == "EMPTY" and tags.whitted.shape != "MESH":
            exporter.warn(
                f"object '{obj.name}' is an Empty tagged {tags.whitted.shape.title()}: only "
                "mesh objects can carry a Whitted shape; it is not rendered"
            )
    MESH_CACHE.keep_only(exporter.meshes.keys())
    warnings = list(exporter.warnings)
    if skipped:
        names = ", ".join(f"'{name}'" for name in sorted(set(skipped))[:5])
        warnings.append(
            f"Whitted skipped {len(skipped)} light(s) it cannot render ({names}): it renders "
            "point and sun lights and square or rectangular area lights"
        )
    camera = export_camera(scene, depsgraph, settings)
    result = core.Scene(
        camera=camera, shapes=exporter.shapes, lights=lights, ambient=world, background=world
    )
    return result, settings, warnings


def whitted_source(instance):
    """The object to read an instance's Whitted settings from. An instance's `object` is a
    temporary copy made for the iteration: reading a property group there creates it on the
    copy, which Blender never frees (50,000 instances leaked 25-33 MB a render, and Blender's
    "Not freed memory blocks" at exit). `instance_object` is the evaluated object it copies,
    with the same settings, owned by the depsgraph."""
    if instance.is_instance and instance.instance_object is not None:
        return instance.instance_object
    return instance.object


def render_settings(scene) -> core.RenderSettings:
    render = scene.render
    scale = render.resolution_percentage / 100.0
    width = int(render.resolution_x * scale)
    height = int(render.resolution_y * scale)
    for field, value in (("resolution_x", width), ("resolution_y", height)):
        if value < 1:
            raise core.SceneError(
                f"scene '{scene.name}'",
                f"render {field}",
                f"{value} pixels after the {render.resolution_percentage}% scale; "
                "set Output Properties > Format > Resolution to at least 1",
            )
    threads = render.threads if render.threads_mode == "FIXED" else 0
    settings = scene.whitted
    return core.RenderSettings(
        width=width,
        height=height,
        tile_size=settings.tile_size,
        threads=threads,
        region=_border_region(render, width, height),
        max_depth=settings.max_depth,
        pixel_samples=settings.pixel_samples,
        pixel_sampling=settings.pixel_sampling.lower(),
        shadow_samples=settings.shadow_samples,
        shadow_sampling=settings.shadow_sampling.lower(),
        seed=settings.seed,
    )


def _border_region(render, width, height):
    """The render border as core's region (y from the top), in whole pixels as Blender counts
    them: float32 border fraction times size, truncated."""
    if not render.use_border:
        return None

    def pixel(fraction, size):
        return int(np.float32(fraction) * np.float32(size))

    x_min, x_max = pixel(render.border_min_x, width), pixel(render.border_max_x, width)
    y_min, y_max = pixel(render.border_min_y, height), pixel(render.border_max_y, height)
    if x_max <= x_min or y_max <= y_min:
        return None  # Blender renders the whole frame for an empty border
    return (x_min, height - y_max, x_max - x_min, y_max - y_min)


def export_camera(scene, depsgraph, settings: core.RenderSettings) -> core.Camera:
    if scene.camera is None:
        raise core.SceneError(
            f"scene '{scene.name}'",
            "camera",
            "there is no active camera; add a camera and set it in Scene Properties > Camera",
        )
    camera = scene.camera.evaluated_get(depsgraph)
    owner = f"camera '{camera.name}'"
    if camera.type != "CAMERA":
        raise core.SceneError(owner, "type", f"is a {camera.type} object; use a camera object")
    if camera.data.type != "PERSP":
        raise core.SceneError(
            owner,
            "lens type",
            f"is {camera.data.type}; Whitted renders perspective cameras only: "
            "set Camera Properties > Lens > Type to Perspective",
        )
    projection = camera.calc_matrix_camera(
        depsgraph,
        x=settings.width,
        y=settings.height,
        scale_x=scene.render.pixel_aspect_x,
        scale_y=scene.render.pixel_aspect_y,
    )
    fovy = math.degrees(2.0 * math.atan(1.0 / projection[1][1]))
    rotation = camera.matrix_world.to_3x3().normalized()
    eye, view = camera.matrix_world.translation, -rotation.col[2]
    aperture, focus = _depth_of_field(scene, camera, eye, view)
    return core.Camera(
        eye=tuple(eye),
        view=tuple(view),
        up=tuple(rotation.col[1]),
        fovy=fovy,
        name=camera.name,
        aperture_radius=aperture,
        focal_distance=focus,
        # The off-axis terms of Blender's projection: the lens shift, in half-widths/heights
        shift=(float(projection[0][2]), float(projection[1][2])),
    )


def _depth_of_field(scene, camera, eye, view) -> tuple[float, float]:
    """(aperture radius, focus distance) from Blender's own camera depth of field, as
    Cycles reads it: radius = focal length / (2 f-stop), in scene units; the focus object's
    distance along the view, else the focus distance. A pinhole when depth of field is off."""
    dof = camera.data.dof
    if not dof.use_dof:
        return 0.0, 10.0
    focus = dof.focus_distance
    if dof.focus_object is not None:
        focus = float((dof.focus_object.matrix_world.translation - eye).dot(view))
    if focus <= 0.0:
        raise core.SceneError(
            f"camera '{camera.name}'",
            "depth of field focus",
            f"is {focus:.4g} in front of the camera; put the focus object in front of it or "
            "set a positive Focus Distance",
        )
    radius = camera.data.lens * 1e-3 / (2.0 * dof.aperture_fstop)
    return radius / scene.unit_settings.scale_length, focus


def world_colour(world) -> tuple[float, float, float]:
    if world is None:
        return (0.0, 0.0, 0.0)
    background = find_node(world, "BACKGROUND")
    if background is not None:
        colour, strength = background.inputs[0].default_value, background.inputs[1].default_value
        return tuple(float(c) * strength for c in colour[:3])
    return tuple(float(c) for c in world.color)


def _point_light(obj, matrix_world) -> core.PointLight:
    light = obj.data
    intensity = tuple(float(c) * light.energy * WATTS_TO_INTENSITY for c in light.color)
    return core.PointLight(
        position=tuple(matrix_world.translation),
        intensity=intensity,
        attenuation=tuple(light.whitted.attenuation),
        name=obj.name,
    )


def _sun_light(obj, matrix_world) -> core.DirectionalLight:
    """A sun: light along the object's -Z axis, irradiance colour x strength / pi (a white
    diffuse surface facing it is then as bright as Cycles makes it)."""
    light = obj.data
    axes = np.array(matrix_world.to_3x3(), float)
    return core.DirectionalLight(
        direction=tuple(-axes[:, 2]),
        intensity=tuple(float(c) * light.energy / math.pi for c in light.color),
        name=obj.name,
    )


def _area_light(obj, matrix_world) -> core.AreaLight | None:
    """A square or rectangular area light, its edges along the object's x and y axes (so
    scaled and rotated with it), lighting both sides; None for disk and ellipse shapes."""
    light = obj.data
    if light.shape not in {"SQUARE", "RECTANGLE"}:
        return None
    width = light.size
    height = light.size if light.shape == "SQUARE" else light.size_y
    axes = np.array(matrix_world.to_3x3(), float)
    intensity = tuple(float(c) * light.energy * WATTS_TO_INTENSITY for c in light.color)
    return core.AreaLight(
        centre=tuple(matrix_world.translation),
        edge_u=tuple(axes[:, 0] * width),
        edge_v=tuple(axes[:, 1] * height),
        intensity=intensity,
        attenuation=tuple(light.whitted.attenuation),
        name=obj.name,
    )
