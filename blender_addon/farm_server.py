"""A farm worker's Blender, kept running between tasks: `blender -b --addons whitted --python
farm_server.py` reads one request per line on stdin (JSON: the scene, its frames, its border,
threads and the folder to write to), renders it with Blender's own render operator, as `-f`
does, and answers on stdout with one line, WHITTED_FARM_DONE or WHITTED_FARM_FAILED and JSON.

Why: a `blender -b` per task pays Blender's start and the add-on's import (1.3 s here) for
every border; kept warm, a task costs its render. The scene is opened once and again only when
its file changes (path, size or modification time). A script run by Blender, not part of the
add-on's modules: the worker (core/farm/warm_blender.py) starts it from this checkout or the
installed add-on's folder. It exits on end of input, on "stop", or when idle for IDLE_S.
"""

import json
import os
import select
import sys
import traceback

import bpy

IDLE_S = float(os.environ.get("WHITTED_FARM_IDLE_S", "600"))  # then give the memory back
DONE, FAILED, READY = "WHITTED_FARM_DONE", "WHITTED_FARM_FAILED", "WHITTED_FARM_READY"


class RequestError(Exception):
    """A request this scene cannot honour, said in the user's terms: answered without a
    traceback, which only unexpected failures get."""


def answer(kind: str, **fields) -> None:
    print(kind, json.dumps(fields), flush=True)


# What a request changes of the scene's render settings, put back as the file has them before
# the next request, so that each renders the file as a fresh `blender -b` would
TOUCHED = ("engine", "threads_mode", "threads", "use_border", "use_crop_to_border",
           "border_min_x", "border_max_x", "border_min_y", "border_max_y", "filepath",
           "use_file_extension")  # fmt: skip


def open_scene(request: dict, opened: dict):
    """The request's scene, as its .blend file has it: opened unless it is open already and
    unchanged on disk, else with what earlier requests changed put back."""
    stamp = [request["scene"], *request["stamp"]]
    if opened.get("stamp") != stamp:
        try:
            bpy.ops.wm.open_mainfile(filepath=request["scene"], load_ui=False)
        except RuntimeError as error:
            opened.clear()  # whatever is open now is not a scene of ours
            raise RequestError(f"{request['scene']}: Blender cannot open it: {error}") from None
        scene = bpy.context.scene
        opened.update(stamp=stamp, frame=scene.frame_current,
                      format=scene.render.image_settings.file_format,
                      settings={name: getattr(scene.render, name) for name in TOUCHED})  # fmt: skip
        return scene
    scene = bpy.context.scene
    for name, value in opened["settings"].items():
        setattr(scene.render, name, value)
    scene.render.image_settings.file_format = opened["format"]
    scene.frame_set(opened["frame"])
    return scene


def set_border(render, request: dict) -> tuple | None:
    """Render only the request's border, cropped, as `core.farm.jobs` cuts it: (x, y, width,
    height, frame width, frame height) in pixels, rows from the top, or None for whole
    frames. The fractions sit half a pixel inside each edge, so that Blender's float32
    arithmetic (fraction x size, truncated) gives exactly the pixels asked for."""
    w = int(render.resolution_x * render.resolution_percentage / 100)
    h = int(render.resolution_y * render.resolution_percentage / 100)
    if request.get("part"):
        c, r, columns, rows = request["part"]
        x0, x1 = w * c // columns, w * (c + 1) // columns
        y0, y1 = h * r // rows, h * (r + 1) // rows
        if x1 <= x0 or y1 <= y0:  # more parts than pixels: some parts would be empty
            raise RequestError(
                f"--split {columns}x{rows}: the frame is only {w} x {h} pixels; "
                "split it into fewer parts"
            )
    elif request.get("border"):
        x, y, width, height = request["border"]
        x0, x1, y0, y1 = x, x + width, y, y + height
    else:
        render.use_border = False
        return None
    render.use_border = True
    render.use_crop_to_border = True
    render.border_min_x = (x0 + 0.5) / w
    render.border_max_x = min(1.0, (x1 + 0.5) / w)
    render.border_min_y = (h - y1 + 0.5) / h  # Blender counts rows from the bottom
    render.border_max_y = min(1.0, (h - y0 + 0.5) / h)
    return (x0, y0, x1 - x0, y1 - y0, w, h)


def probe(scene) -> list[int]:
    """The frame's size in pixels, the frame range and the current frame."""
    render = scene.render
    w = int(render.resolution_x * render.resolution_percentage / 100)
    h = int(render.resolution_y * render.resolution_percentage / 100)
    return [w, h, scene.frame_start, scene.frame_end, scene.frame_current]


def render_request(request: dict, opened: dict) -> dict:
    scene = open_scene(request, opened)
    if request.get("probe"):
        return {"probe": probe(scene)}
    render = scene.render
    try:
        render.engine = "WHITTED"  # as -E WHITTED
    except TypeError:
        raise RequestError(
            "Blender has no WHITTED render engine: the Whitted add-on is not installed or "
            "not enabled on this worker (--addon names its module)"
        ) from None
    if request.get("threads"):
        render.threads_mode = "FIXED"
        render.threads = request["threads"]
    border = set_border(render, request)
    render.image_settings.file_format = "PNG"  # as -F PNG
    render.use_file_extension = True
    written = []
    for frame in request["frames"]:
        scene.frame_set(frame)
        base = os.path.join(request["folder"], f"frame_{frame:06d}")
        render.filepath = base
        # The engine reports its errors (a scene it cannot render) to the operator, which
        # raises them here as RuntimeError: the request fails with Whitted's message, as
        # -f's exit status and log would
        try:
            bpy.ops.render.render(write_still=True)
        except RuntimeError as error:
            raise RequestError(f"frame {frame}: {error}".strip()) from None
        if not os.path.exists(base + ".png"):
            raise RequestError(f"frame {frame}: Blender wrote no image")
        written.append(frame)
    return {"frames": written, "border": border}


def serve() -> None:
    opened: dict = {}
    answer(READY, blender=bpy.app.version_string)
    while True:
        ready, _, _ = select.select([sys.stdin], [], [], IDLE_S)
        line = sys.stdin.readline() if ready else ""
        if not line or line.strip() == "stop":
            return
        try:
            answer(DONE, **render_request(json.loads(line), opened))
        except RequestError as error:
            answer(FAILED, error=str(error))
        except Exception as error:  # noqa: BLE001 - each request's failure is its answer
            traceback.print_exc(file=sys.stdout)
            answer(FAILED, error=f"{type(error).__name__}: {error}".strip())


if __name__ == "__main__":  # run by Blender as --python farm_server.py
    serve()
