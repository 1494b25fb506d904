"""Blender depsgraph -> core.Scene: the add-on's only reader of Blender scene data.

One module per Blender data type, each with a `convert`: `settings` (render settings),
`camera`, `world`, `light`, `instances` (objects, through `mesh`, `material` and `csg`).
"""

from __future__ import annotations

import numpy as np

from .. import core
from . import camera, light, passes, settings, world
from . import view as view  # the viewport's reader of its 3D view, export.view
from .instances import Exporter
from .mesh import MeshCache

# Curves, text, surfaces and metaballs are listed too as the mesh instances they evaluate to
GEOMETRY_TYPES = {"MESH"}


def convert(
    depsgraph,
    mesh_cache: MeshCache | None = None,
    view_camera: core.Camera | None = None,
    with_passes: bool = False,
) -> tuple[core.Scene, core.RenderSettings, list[str]]:
    """Export the evaluated scene. Returns (scene, settings, warnings); raises SceneError.
    `mesh_cache` is the caller's `MeshCache`, kept from one export to the next (the final
    render's, the viewport's); without one, every mesh is converted afresh. `view_camera`
    (the viewport's, `view.camera`) stands for the scene camera, which need not exist.
    `with_passes`: the settings ask for the view layer's passes (the final render's)."""
    mesh_cache = MeshCache() if mesh_cache is None else mesh_cache
    scene = depsgraph.scene
    render = settings.convert(scene)
    if with_passes:
        passes.apply(render, depsgraph.view_layer, scene.world)
    exporter = Exporter(depsgraph, mesh_cache)
    environment, background, ambient = world.convert(scene.world, exporter.warn)
    holdouts = holdout_objects(depsgraph.view_layer)
    lights = []
    for instance in depsgraph.object_instances:
        obj = instance.object
        tags = whitted_source(instance)
        matrix = np.array(instance.matrix_world, dtype=float)
        if obj.type in GEOMETRY_TYPES:
            holdout = any(
                o is not None and (o.original.is_holdout or o.original.name_full in holdouts)
                for o in (obj, instance.parent if instance.is_instance else None)
            )
            exporter.add_instance(obj, matrix, tags, holdout)
        elif obj.type == "LIGHT":
            lights.append(light.convert(obj, instance.matrix_world, exporter.warn))
        elif obj.type == "EMPTY" and tags.whitted.shape != "MESH":
            exporter.warn(
                f"object '{obj.name}' is an Empty tagged {tags.whitted.shape.title()}: only "
                "mesh objects can carry a Whitted shape; it is not rendered"
            )
    mesh_cache.keep_only(exporter.meshes.keys())
    # A light instanced many times warns once
    warnings = list(dict.fromkeys(exporter.warnings))
    if view_camera is None:
        view_camera = camera.convert(scene, depsgraph, render)
    result = core.Scene(
        camera=view_camera,
        shapes=exporter.shapes,
        lights=lights,
        ambient=ambient,
        background=background,
        environment=environment,
    )
    return result, render, warnings


def holdout_objects(view_layer) -> set[str]:
    """Names (name_full) of the objects in the view layer's holdout collections (the
    Outliner's Holdout switch), with their child collections' objects."""
    found, stack = set(), [view_layer.layer_collection]
    while stack:
        layer_collection = stack.pop()
        if layer_collection.holdout:
            found.update(o.name_full for o in layer_collection.collection.all_objects)
        else:
            stack.extend(layer_collection.children)
    return found


def whitted_source(instance):
    """The object to read an instance's Whitted settings from. An instance's `object` is a
    temporary copy made for the iteration: reading a property group there creates it on the
    copy, which Blender never frees (50,000 instances leaked 25-33 MB a render, and Blender's
    "Not freed memory blocks" at exit). `instance_object` is the evaluated object it copies,
    with the same settings, owned by the depsgraph."""
    if instance.is_instance and instance.instance_object is not None:
        return instance.instance_object
    return instance.object
