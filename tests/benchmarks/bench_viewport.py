"""Rendered viewport benchmark (Blender 5.0 bpy module): the final scene in a 640 x 360 view
through its camera, driven as Blender drives the engine (view_update, view_draw's view check),
without a window's drawing.

Prints:
  viewport_first_image_unloaded_s  Rendered switched on in a process whose kernels are not
                               loaded yet, to the first coarse image: they load from the
                               (warm) disk cache meanwhile
  viewport_first_image_s       the same with the kernels in memory, as Blender's window has
                               them: the add-on loads them once the warm-up is done
                               (kernel_status._preload), and any later switch finds them
  viewport_update_s            an object moved (view_update), to the first updated image
  viewport_orbit_s             the view moved (view_draw), to the first image of the new view
  viewport_pass_N_s            when each pass of the first render is complete
Medians of 7 (the cold figure: one). Writes results/viewport.png, the passes over time.
"""

import statistics
import sys
import time
from pathlib import Path

import bpy  # before addon_utils, which is one of the modules bpy brings

ROOT = Path(__file__).resolve().parents[2]
RESULTS = Path(__file__).resolve().parent / "results"
RUNS = 7


def camera_view(view_module, scene, width=640, height=360):
    depsgraph = bpy.context.evaluated_depsgraph_get()
    camera = scene.camera.evaluated_get(depsgraph)
    rows = view_module._rows
    return view_module.View(
        width=width,
        height=height,
        view_matrix=rows(camera.matrix_world.inverted()),
        window_matrix=rows(camera.calc_matrix_camera(depsgraph, x=width, y=height)),
        perspective="CAMERA",
        clip_end=1000.0,
        border=None,
    )


def first_image_after(session, change) -> float:
    """Seconds from calling change() to the first image of the render it starts."""
    start = time.perf_counter()
    change()
    image = session.renderer.wait_for(session.renderer.generation, 0)
    assert image is not None, session.status()
    return time.perf_counter() - start


def main():
    import addon_utils

    addon_utils.enable("whitted", default_set=True)
    viewport = sys.modules["whitted.engine.viewport"]
    view_module = sys.modules["whitted.export"].view
    bpy.ops.wm.open_mainfile(filepath=str(ROOT / "sample_blends" / "final_scene.blend"))
    scene = bpy.context.scene
    view = camera_view(view_module, scene)

    passes = []
    session = viewport.ViewportSession(
        on_image=lambda image: image.complete and passes.append(time.perf_counter())
    )
    depsgraph = bpy.context.evaluated_depsgraph_get()
    start = time.perf_counter()
    cold = first_image_after(session, lambda: session.update(depsgraph, view))
    session.renderer.wait_for(session.renderer.generation, len(session.renderer.passes) - 1, 600)
    pass_times = [t - start for t in passes]
    print(f"viewport_first_image_unloaded_s: {cold:.3f}")
    session.close()

    firsts, updates, orbits = [], [], []
    mover = next(o for o in scene.objects if o.type == "MESH" and o.whitted.shape != "MESH")
    for run in range(RUNS):
        first, update, orbit = one_run(viewport, view_module, view, mover, run)
        firsts.append(first)
        updates.append(update)
        orbits.append(orbit)
    print(f"viewport_first_image_s: {statistics.median(firsts):.3f}")
    print(f"viewport_update_s: {statistics.median(updates):.3f}")
    print(f"viewport_orbit_s: {statistics.median(orbits):.3f}")
    for index, seconds in enumerate(pass_times):
        print(f"viewport_pass_{index}_s: {seconds:.3f}")
    chart(pass_times)


def one_run(viewport, view_module, view, mover, run):
    """(first image, update, orbit) seconds of a new session."""
    session = viewport.ViewportSession()
    depsgraph = bpy.context.evaluated_depsgraph_get()
    first = first_image_after(session, lambda: session.update(depsgraph, view))

    def move():
        mover.location.x += 0.05 if run % 2 == 0 else -0.05
        session.update(bpy.context.evaluated_depsgraph_get(), view)

    update = first_image_after(session, move)
    matrix = [list(row) for row in view.view_matrix]
    matrix[0][3] += 0.02 * (run + 1)
    orbited = view_module.View(**{**view.__dict__, "view_matrix": tuple(map(tuple, matrix))})
    orbit = first_image_after(session, lambda: session.view_moved(depsgraph, orbited))
    session.close()
    return first, update, orbit


def chart(pass_times):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    RESULTS.mkdir(exist_ok=True)
    labels = ["1/8, 1 ray", "1/4, 1 ray", "1/2, 1 ray", "full, 1 ray", "full, settings"]
    fig, ax = plt.subplots(figsize=(7, 3.5))
    ax.barh(labels[: len(pass_times)], pass_times)
    ax.axvline(0.3, color="red", linestyle="--", label="0.3 s: first image goal")
    ax.set_xscale("log")
    ax.set_xlabel("seconds from Rendered switched on (kernels loading from the disk cache)")
    ax.set_title("Final scene, 640 x 360 viewport: when each pass is complete")
    ax.legend()
    fig.tight_layout()
    fig.savefig(RESULTS / "viewport.png", dpi=100)
    print(f"chart: {RESULTS / 'viewport.png'}")


if __name__ == "__main__":
    main()
