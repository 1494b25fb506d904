"""Run inside Blender's window: render each material's preview thumbnail (as the Material
tab and the asset browser do: `ed.lib_id_generate_preview`), one at a time, and count the
preview renders Whitted's engine made. Writes, to the path after `--`, JSON of each material's
preview as RGB rows (row 0 at the top) and the count. Adds a pink node material first."""

import json
import sys
import time

import bpy

from tests.support.preview_pixels import rgb_rows
from tests.support.window_timer import register_step, written

OUT = sys.argv[sys.argv.index("--") + 1]
TIMEOUT_S = 60
final = sys.modules["whitted.engine.final"]
seen = {"previews rendered by Whitted": 0, "materials": {}}
original_render = final.render


def counting_render(engine, depsgraph):
    seen["previews rendered by Whitted"] += bool(engine.is_preview)
    original_render(engine, depsgraph)


final.render = counting_render
# A node material as a user makes one (Principled, base colour pink), besides the sample's
pink = bpy.data.materials.new("Pink")
pink.use_nodes = True
pink.node_tree.nodes["Principled BSDF"].inputs["Base Color"].default_value = (1.0, 0.3, 0.55, 1)
queue = list(bpy.data.materials)
state = {"material": None, "since": 0.0}


def generate_preview(material):
    with bpy.context.temp_override(id=material):
        bpy.ops.ed.lib_id_generate_preview()


def tick():
    if sys.modules["whitted.core"].jit.warmup_process.shared_warmup().status().state == "running":
        return 0.25
    material = state["material"]
    if material is not None:
        rows = rgb_rows(material.preview)
        blank = max(max(max(pixel) for pixel in row) for row in rows) <= 0.0
        if blank and time.monotonic() - state["since"] < TIMEOUT_S:
            return 0.25
        seen["materials"][material.name] = rows
    if not queue:
        with open(OUT, "w") as f:
            json.dump(seen, f)
        bpy.ops.wm.quit_blender()
        return None
    if not written(lambda: generate_preview(queue[0])):
        state["material"] = None  # the last one is recorded: try this one at the next tick
        return 0.25
    state["material"] = queue.pop(0)
    state["since"] = time.monotonic()
    return 0.25


register_step(tick, OUT)
