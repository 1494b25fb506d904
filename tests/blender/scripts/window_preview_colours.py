"""Run inside Blender's window: each material's preview thumbnail (`ed.lib_id_generate_preview`,
as the Material tab makes it), first with Whitted, then with Cycles as the render engine; then
an F12 render with Whitted of the sample scene with the materials on its ball. Writes, to the
path after `--`, JSON: per engine and material the thumbnail's RGB rows (as displayed, row 0
at the top); the F12 image's rows; the count of previews Whitted's engine rendered.

A thumbnail is taken once its pixels have held still for a second (Cycles refines its in
passes; Whitted's comes in one)."""

import json
import sys
import time

import bpy

from tests.support.preview_pixels import rgb_rows
from tests.support.window_timer import register_step, written

OUT = sys.argv[sys.argv.index("--") + 1]
TIMEOUT_S = 90
final = sys.modules["whitted.engine.final"]
seen = {"previews rendered by Whitted": 0, "thumbnails": {}, "f12": {}}
original_render = final.render


def counting_render(engine, depsgraph):
    seen["previews rendered by Whitted"] += bool(engine.is_preview)
    original_render(engine, depsgraph)


final.render = counting_render


def principled(name, colour):
    material = bpy.data.materials.new(name)
    material.use_nodes = True
    node = material.node_tree.nodes["Principled BSDF"]
    node.inputs["Base Color"].default_value = (*colour, 1.0)
    return material


# Saturated colours as users pick them, and a pale one (linear RGB)
MATERIALS = [principled("Red", (0.8, 0.02, 0.02)), principled("Pink", (1.0, 0.3, 0.55)),
             principled("Teal", (0.02, 0.5, 0.45))]  # fmt: skip
queue = [(engine, m) for engine in ("WHITTED", "CYCLES") for m in MATERIALS]
state = {"job": None, "since": 0.0, "last": None, "still_since": 0.0}


def f12():
    """The sample's glass ball wearing each material in turn, rendered by Whitted."""
    scene = bpy.context.scene
    scene.render.engine = "WHITTED"
    scene.render.resolution_percentage = 50
    ball = bpy.data.objects["Glass Ball"]
    for material in MATERIALS:
        ball.material_slots[0].material = material
        bpy.ops.render.render()
        image = bpy.data.images["Render Result"]
        path = f"{OUT}.{material.name}.png"
        image.save_render(path)
        seen["f12"][material.name] = path


def start_preview(engine, material):
    bpy.context.scene.render.engine = engine
    with bpy.context.temp_override(id=material):
        bpy.ops.ed.lib_id_generate_preview()


def tick():
    if sys.modules["whitted.core"].jit.warmup_process.shared_warmup().status().state == "running":
        return 0.25
    job = state["job"]
    if job is not None:
        engine, material = job
        rows = rgb_rows(material.preview)
        waited = time.monotonic() - state["since"]
        if rows != state["last"]:
            state["last"], state["still_since"] = rows, time.monotonic()
        lit = max(max(max(pixel) for pixel in row) for row in rows) > 0.0
        still = time.monotonic() - state["still_since"] > 1.0
        if not (lit and still and waited > 2.0) and waited < TIMEOUT_S:
            return 0.25
        seen["thumbnails"].setdefault(engine, {})[material.name] = rows
    if not queue:
        # Blender may still refuse writes as the last preview job ends: then at the next tick
        if not written(f12):
            return 0.25
        with open(OUT, "w") as f:
            json.dump(seen, f)
        bpy.ops.wm.quit_blender()
        return None
    if not written(lambda: start_preview(*queue[0])):
        state["job"] = None  # the last one is recorded: try this one at the next tick
        return 0.25
    state["job"] = queue.pop(0)
    state["since"], state["last"] = time.monotonic(), None
    return 0.25


register_step(tick, OUT)
