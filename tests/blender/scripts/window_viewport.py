"""Run inside Blender's window: switch the largest 3D view to Rendered shading, wait for
Whitted's last pass, screenshot, move the blue ball 1 m along +x, wait again, screenshot, then
switch back to Solid. What it saw goes as JSON to the path after `--`, with the screenshots
beside it (`.before.png`, `.after.png`). A chain of timers, one step a tick, so that Blender
draws between the steps as it would for a user."""

import json
import sys
import threading
import time

import bpy

OUT = sys.argv[sys.argv.index("--") + 1]
seen = {}


def viewport():
    return sys.modules["whitted.engine.viewport"]


def area():
    window = bpy.context.window_manager.windows[0]
    views = [a for a in window.screen.areas if a.type == "VIEW_3D"]
    return max(views, key=lambda a: a.width * a.height)


def session():
    return next(iter(viewport()._sessions), None)


def finished():
    s = session()
    return s is not None and not s.renderer.busy() and s.texture.image is s.renderer.latest()


def when_warm():
    if sys.modules["whitted.core"].jit.warmup_process.shared_warmup().status().state == "running":
        return 0.25, when_warm
    space = area().spaces.active
    space.overlay.show_overlays = False  # the ball's outline would move with it
    space.region_3d.view_perspective = "CAMERA"
    space.shading.type = "RENDERED"
    seen["switched"] = time.perf_counter()
    return 0.02, first_image


def first_image():
    s = session()
    if s is None or s.renderer.latest() is None:
        return 0.02, first_image
    seen["first image s"] = time.perf_counter() - seen["switched"]
    return 0.1, until_finished(before)


def until_finished(then):
    def wait():
        area().tag_redraw()
        return (0.3, then) if finished() else (0.1, wait)

    return wait


def before():
    seen["status"] = session().status()
    bpy.ops.screen.screenshot(filepath=OUT + ".before.png")
    s = session()
    seen["generation"] = s.renderer.generation
    seen["counts before"] = [s.exports, s.reframes, s.meshes.conversions]
    bpy.data.objects["Blue"].location.x += 1.0
    seen["moved"] = time.perf_counter()
    return 0.02, updated


def updated():
    s = session()
    image = s.renderer.latest()
    if image is None or image.generation == seen["generation"]:
        return 0.02, updated
    seen["view_update after move s"] = s.changed_at - seen["moved"]
    return 0.1, until_finished(after)


def after():
    s = session()
    seen["counts after"] = [s.exports, s.reframes, s.meshes.conversions]
    bpy.ops.screen.screenshot(filepath=OUT + ".after.png")
    seen["renderer"] = s.renderer
    area().spaces.active.shading.type = "SOLID"
    return 0.5, switched_away


def switched_away():
    renderer = seen.pop("renderer")
    seen["render thread alive"] = renderer._thread.is_alive()
    seen["sessions left"] = len(viewport()._sessions)
    seen["threads"] = sorted(t.name for t in threading.enumerate())
    with open(OUT, "w") as f:
        json.dump(seen, f)
    bpy.ops.wm.quit_blender()
    return None, None


step = [when_warm]


def tick():
    interval, step[0] = step[0]()
    return interval


bpy.app.timers.register(tick, first_interval=2.0)
