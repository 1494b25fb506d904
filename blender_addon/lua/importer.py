"""File > Import > CS488 Lua Scene: a report or A4 scene script as Blender data.

The script runs in core's sandbox, in a child process within the import's time and memory
limits, with every call checked (a mistake is reported with its line, and nothing is
imported). From Blender's window the import is modal: Blender stays usable while the script
runs, the status bar shows it, and Esc stops it at once (the child is killed); from a
script or under `blender -b` it runs to the end before the operator returns.

Each gr.render call becomes a new scene named after its image, and the window shows the
first: the user's own scene is left exactly as it was (its objects, camera, World, render and
colour settings). A new scene gets the objects under the call's node (`lua_build`), the
camera from eye/view/up/fovy and the depth of field, the lights, the world colour from the
ambient term, and the render settings from gr.render, with the Raw view transform: the render
then writes the same PNG as `python -m core render`, which writes the renderer's values as
the original course project's program did. Imported Into Current Scene instead, the first
call's objects, camera and lights are added to the current scene and none of its settings is
changed (the scene's camera is set only if it has none), and the report says so.
"""

from __future__ import annotations

import contextlib
import math
import os
import time
from pathlib import Path

import bpy
import numpy as np
from bpy_extras.io_utils import ImportHelper
from mathutils import Matrix

from ..blender_data import place
from ..compat import give_nodes
from ..core.cs488 import ScriptError, ScriptLimits, ScriptRun, load_script
from ..core.cs488.sandbox import (
    DEFAULT_LIMITS,
    MAX_SCRIPT_MEMORY_MIB,
    MAX_SCRIPT_SECONDS,
    MIN_SCRIPT_MEMORY_MIB,
    MIN_SCRIPT_SECONDS,
)
from ..export.light import WATTS_TO_INTENSITY
from ..reporting import report_internal_failure
from .build import Y_UP_TO_Z_UP, Builder

POLL_S = 0.1


NEW_SCENE, CURRENT_SCENE = "NEW_SCENE", "CURRENT_SCENE"


def import_script(
    context, path: str | Path, limits=DEFAULT_LIMITS, anywhere=False, into=NEW_SCENE
) -> list:
    """Run the script, then build every gr.render call of it; returns the scenes. Raises
    ScriptError."""
    calls = load_script(path, print_line=print, anywhere=anywhere, limits=limits,
                        notice=lambda text: print(f"Whitted: {text}", flush=True))  # fmt: skip
    return build_scenes(context, Path(path), calls, into)


def build_scenes(context, path: Path, calls: list, into: str = NEW_SCENE) -> list:
    """A new scene for each gr.render call, the window switched to the first (`into` is
    NEW_SCENE); or the first call's objects, camera and lights added to the current scene,
    whose settings stay as they are (CURRENT_SCENE)."""
    if not calls:
        raise ScriptError(f"{path.name}: the script never calls gr.render: nothing to import")
    scenes, shared = [], {}
    for number, call in enumerate(calls):
        new = into == NEW_SCENE or number > 0
        scene = bpy.data.scenes.new(call.output.stem) if new else context.scene
        collection = bpy.data.collections.new(f"{path.stem}: {call.output.name}")
        scene.collection.children.link(collection)
        root = bpy.data.objects.new(f"{path.stem} (y up)", None)
        collection.objects.link(root)
        root.matrix_world = Matrix(Y_UP_TO_Z_UP.tolist())
        Builder(collection, shared).node(call.root, root, np.eye(4))
        camera = _camera(call, collection, root)
        if new or scene.camera is None:
            scene.camera = camera
        for number_of_light, light in enumerate(call.lights, start=1):
            _light(light, f"Light {number_of_light}", collection, root)
        if new:
            _configure(scene, call)
        scenes.append(scene)
    window = context.window or next(iter(context.window_manager.windows), None)
    if into == NEW_SCENE and window is not None:
        window.scene = scenes[0]  # the user sees what was imported; their scene is unchanged
    # Every new scene's depsgraph made and evaluated now, its parented objects placed (a
    # scene no window shows has none until asked for one)
    for scene in scenes:
        for layer in scene.view_layers:
            layer.depsgraph.update()
    return scenes


def _camera(call, collection, root):
    camera = call.scene.camera
    data = bpy.data.cameras.new("Camera")
    data.sensor_fit = "VERTICAL"
    data.angle_y = math.radians(camera.fovy)
    data.clip_start, data.clip_end = 1e-3, 1e7
    if camera.aperture_radius > 0:
        data.dof.use_dof = True
        data.dof.focus_distance = camera.focal_distance
        # The export reads the radius as focal length / (2 f-stop), in scene units
        data.dof.aperture_fstop = data.lens * 1e-3 / (2.0 * camera.aperture_radius)
    forward = _unit(camera.view)
    right = _unit(np.cross(forward, camera.up))
    up = np.cross(right, forward)
    local = np.eye(4)
    local[:3, 0], local[:3, 1], local[:3, 2], local[:3, 3] = right, up, -forward, camera.eye
    obj = bpy.data.objects.new("Camera", data)
    collection.objects.link(obj)
    obj.parent = root
    place(obj, local)
    return obj


def _light(spec, name, collection, root):
    """A point light, or a rectangle area light facing down the script's y (its edges along
    the script's x and -z, as the core light's)."""
    core_light = spec.core
    colour = np.array(spec.colour, float)
    brightest = float(colour.max())
    kind = "POINT" if spec.size is None else "AREA"
    data = bpy.data.lights.new(name, kind)
    data.color = tuple(colour / brightest) if brightest > 0 else (1.0, 1.0, 1.0)
    data.energy = brightest / WATTS_TO_INTENSITY  # the export's conversion, inverted
    data.whitted.model = "CS488"  # the script's lights, as the command line renders them
    data.whitted.attenuation = spec.falloff
    local = np.eye(4)
    local[:3, 3] = spec.position
    if kind == "POINT":
        data.shadow_soft_size = 0.0
    else:
        data.shape = "RECTANGLE"
        data.size, data.size_y = spec.size
        local[:3, 0] = _unit(core_light.edge_u)
        local[:3, 1] = _unit(core_light.edge_v)
        local[:3, 2] = np.cross(local[:3, 0], local[:3, 1])
    obj = bpy.data.objects.new(name, data)
    collection.objects.link(obj)
    obj.parent = root
    place(obj, local)
    return obj


def _configure(scene, call) -> None:
    settings = call.settings
    scene.render.engine = "WHITTED"
    scene.render.resolution_x, scene.render.resolution_y = settings.width, settings.height
    scene.render.resolution_percentage = 100
    scene.render.pixel_aspect_x = scene.render.pixel_aspect_y = 1.0
    scene.render.use_border = False
    scene.render.filepath = str(call.output)
    scene.render.image_settings.file_format = "PNG"
    scene.render.image_settings.color_mode = "RGBA"
    scene.render.image_settings.color_depth = "8"  # the bytes the command line writes
    scene.render.dither_intensity = 0.0
    scene.view_settings.view_transform = "Raw"
    scene.view_settings.look = "None"
    scene.view_settings.exposure, scene.view_settings.gamma = 0.0, 1.0
    whitted = scene.whitted
    whitted.max_depth = settings.max_depth
    whitted.pixel_samples = settings.pixel_samples
    whitted.pixel_sampling = settings.pixel_sampling.upper()
    whitted.shadow_samples = settings.shadow_samples
    whitted.shadow_sampling = settings.shadow_sampling.upper()
    whitted.adaptive_shadows = settings.adaptive_shadows
    whitted.seed = settings.seed
    # the report's rule, so the imported scene renders as the script does
    whitted.glass_shadows = settings.glass_shadows.upper()
    whitted.use_caustics_reflective = "reflective" in settings.caustics
    whitted.use_caustics_refractive = "refractive" in settings.caustics
    whitted.use_auto_photons = settings.caustic_photons == "auto"
    if not whitted.use_auto_photons:
        whitted.caustic_photons = settings.caustic_photons
    world = bpy.data.worlds.new(f"{call.output.stem} ambient")
    give_nodes(world)
    background = next(n for n in world.node_tree.nodes if n.type == "BACKGROUND")
    background.inputs[0].default_value = (*call.ambient, 1.0)
    background.inputs[1].default_value = 1.0
    world.color = call.ambient
    # The script's ambient term as the report used it, and its background
    world.whitted.model = "CS488"
    world.whitted.ambient = call.ambient
    scene.world = world


def _unit(vector) -> np.ndarray:
    vector = np.asarray(vector, float)
    return vector / np.linalg.norm(vector)


class WHITTED_OT_import_lua(bpy.types.Operator, ImportHelper):
    """Import a CS488 Lua scene script (the A4 language with the report's extensions)"""

    bl_idname = "import_scene.cs488_lua"
    bl_label = "Import CS488 Lua Scene"
    bl_options = {"REGISTER", "UNDO"}

    filename_ext = ".lua"
    filter_glob: bpy.props.StringProperty(default="*.lua", options={"HIDDEN"})
    time_limit: bpy.props.FloatProperty(
        name="Time Limit (s)",
        description="Stop the script after this many seconds (Esc stops it sooner)",
        default=DEFAULT_LIMITS.seconds, min=MIN_SCRIPT_SECONDS, max=MAX_SCRIPT_SECONDS,
        soft_max=3600.0,
    )  # fmt: skip
    memory_limit: bpy.props.IntProperty(
        name="Memory (MiB)",  # "Memory Limit (MiB)" is cut in the file browser's sidebar
        description="The memory the script may take while it builds the scene",
        default=DEFAULT_LIMITS.memory_mib, min=MIN_SCRIPT_MEMORY_MIB, max=MAX_SCRIPT_MEMORY_MIB,
        soft_max=65536,
    )  # fmt: skip
    into: bpy.props.EnumProperty(
        name="Import Into",
        description="Where the script's scene goes",
        items=[
            (NEW_SCENE, "New Scene", "A scene of its own for each gr.render call, with the "
             "script's camera, lights, World and render settings; the current scene is left "
             "as it was"),
            (CURRENT_SCENE, "Current Scene", "The script's objects, camera and lights added "
             "to the current scene, changing none of its settings (its camera, World, render "
             "and colour management stay as they are)"),
        ],
        default=NEW_SCENE,
    )  # fmt: skip
    allow_outside_files: bpy.props.BoolProperty(
        name="Any Folder",  # "Files Outside Its Folder" is cut in the sidebar
        description="Let the script read meshes and textures outside its own folder tree",
        default=False,
    )

    def limits(self, stop_key: str = "Esc") -> ScriptLimits:
        return ScriptLimits(
            stop_key=stop_key,
            seconds=self.time_limit,
            memory_mib=self.memory_limit,
            seconds_setting="the import's Time Limit",
            memory_setting="the import's Memory (MiB) setting",
            outside_setting="the import's Any Folder option",
        )

    def execute(self, context):
        if bpy.app.background or context.window is None:
            try:  # nothing to keep responsive: run the script to its end here
                scenes = import_script(
                    context, self.filepath, self.limits("Ctrl-C"), self.allow_outside_files,
                    self.into,
                )  # fmt: skip
            except ScriptError as error:
                self.report({"ERROR"}, f"Whitted: {error}")
                return {"CANCELLED"}
            except Exception as error:  # Whitted's own failure, not the script's
                report_internal_failure(self, "import", error)
                return {"CANCELLED"}
            return self._imported(scenes)
        try:
            self._run = ScriptRun(Path(self.filepath), self.allow_outside_files, self.limits())
        except ScriptError as error:
            self.report({"ERROR"}, f"Whitted: {error}")
            return {"CANCELLED"}
        manager = context.window_manager
        self._timer = manager.event_timer_add(POLL_S, window=context.window)
        manager.modal_handler_add(self)
        self._started = time.monotonic()
        self._show(context)
        return {"RUNNING_MODAL"}

    def modal(self, context, event):
        try:
            return self._step(context, event)
        except Exception as error:  # Whitted's own failure: the child must not outlive it
            self._run.cancel()
            self._stop(context)
            report_internal_failure(self, "import", error)
            return {"CANCELLED"}

    def _step(self, context, event):
        if event.type == "ESC":
            self._run.cancel()
            self._stop(context)
            self.report({"INFO"}, f"Whitted: import of {Path(self.filepath).name} cancelled")
            return {"CANCELLED"}
        if event.type != "TIMER":
            return {"PASS_THROUGH"}  # Blender stays usable while the script runs
        if not self._run.poll():
            self._show(context)
            return {"PASS_THROUGH"}
        self._stop(context)
        try:
            scenes = build_scenes(context, Path(self.filepath), self._run.result(), self.into)
        except ScriptError as error:
            self.report({"ERROR"}, f"Whitted: {error}")
            return {"CANCELLED"}
        return self._imported(scenes)

    def cancel(self, context):
        """Blender ends the operator (a file opened, Blender quitting): the child goes too."""
        self._run.cancel()
        self._stop(context)

    def _show(self, context) -> None:
        seconds = time.monotonic() - self._started
        text = (
            f"Whitted: running {Path(self.filepath).name}, {seconds:.0f} s (Esc stops it; "
            f"stopped at {self.time_limit:g} s, the import's Time Limit)"
        )
        # Set only when it changes (once a second), not at every poll: each set redraws the
        # status bar
        if text == getattr(self, "_shown", None):
            return
        self._shown = text
        with contextlib.suppress(AttributeError, RuntimeError, ReferenceError):
            context.workspace.status_text_set(text)

    def _stop(self, context) -> None:
        if self._timer is not None:
            context.window_manager.event_timer_remove(self._timer)
            self._timer = None
        with contextlib.suppress(AttributeError, RuntimeError, ReferenceError):
            context.workspace.status_text_set(None)

    def invoke(self, context, event):
        # The file browser opens in the .blend's folder with an empty name: given no path,
        # Blender would offer the open .blend's own name ("final_scene.blend"), not a script
        if not self.filepath.lower().endswith(".lua"):
            folder = Path(bpy.data.filepath).parent if bpy.data.filepath else Path.home()
            self.filepath = str(folder) + os.sep
        context.window_manager.fileselect_add(self)
        return {"RUNNING_MODAL"}

    def _imported(self, scenes):
        names = ", ".join(f"'{scene.name}'" for scene in scenes)
        name = Path(self.filepath).name
        if self.into == NEW_SCENE:
            self.report({"INFO"}, f"Whitted: imported {name} into new scene(s) {names}")
        else:
            self.report(
                {"INFO"},
                f"Whitted: added {name}'s objects, camera and lights to {names}; its camera, "
                "World, render and colour settings were left as they were (import into a New "
                "Scene for the script's own)",
            )
        return {"FINISHED"}


def _menu_entry(self, context):
    self.layout.operator(WHITTED_OT_import_lua.bl_idname, text="CS488 Lua Scene (.lua)")


def register():
    bpy.utils.register_class(WHITTED_OT_import_lua)
    bpy.types.TOPBAR_MT_file_import.append(_menu_entry)


def unregister():
    bpy.types.TOPBAR_MT_file_import.remove(_menu_entry)
    bpy.utils.unregister_class(WHITTED_OT_import_lua)
