"""Caustics beside Cycles (Blender 5.0 bpy module): the ball lens of bench_caustics (a glass
ball of radius 1, 0.5 above a white plane, a sun 45 degrees from vertical) with a wide sun,
10 degrees across, so that Cycles converges (diffuse bounces 1: plane -> glass -> sun), both
engines through bpy.ops.render.render at 200 x 200 over 4 m of the plane seen from above.

The reference is Cycles at REFERENCE samples a pixel. Each picture's errors against it: the
energy (the plane's mean light) and the brightest 0.2 m square's light (the caustic's peak),
and the 0.2 m blocks' RMS error over the reference's mean (how clean the picture is). Time
is the whole render as Blender runs it (export, Cycles' BVH or Whitted's photon pass, the
pixels), best of two.

Prints, for each engine, its time to a picture within 2% of the energy and 20% of the peak
(the issue's criteria) and within BLOCK_TARGET block error: cycles_converged_s,
whitted_converged_s and their ratio. Writes results/caustics_cycles.png and .csv.

Measured (2026-12-06, 2 cores): Cycles 2.4 s at 64 spp, Whitted 0.38 s at 50 000 photons,
6.3 times sooner (4.3 times before the photons of a sun with an angle started over the
whole hull too). Whitted's block error levels off at 1.6% as photons grow: its caustic's
energy sits 1.2% above Cycles' here (and 1.2% below it under a large area light), while it
matches exact tracers of the ball in tests/core/test_caustics.py (this sun's cone within
0.1%, the area light's patches within 0.2%) and Cycles within 0.1% for a mirror under an
area light: the difference lies in Cycles' glass."""

import math
import time
from pathlib import Path

import bpy  # before addon_utils, which is one of the modules bpy brings
import numpy as np

from tests.benchmarks.bench_sampling import write_chart
from tests.support.cycles import add_ball, add_light, new_scene, node_material, render_with

SIZE = 200
VIEW = 4.0
MIDDLE = (-1.5, 0.0)
SQUARE = 0.2  # m: the peak's square and the blocks
SAMPLES = (16, 64, 256, 1024)
REFERENCE = 4096
PHOTONS = (50_000, 200_000, 800_000)
BLOCK_TARGET = 0.02
FOLDER = Path("/tmp/whitted_bench_caustics_cycles")


def ball_lens(bpy):
    scene = new_scene(bpy)
    scene.render.resolution_x = scene.render.resolution_y = SIZE
    scene.camera.data.ortho_scale = VIEW
    scene.camera.location = (MIDDLE[0], MIDDLE[1], 10.0)
    glass = node_material(bpy, "Glass", "ShaderNodeBsdfGlass", Roughness=0.0, IOR=1.5)[0]
    ball = add_ball(bpy, scene, glass, location=(0.0, 0.0, 1.5), radius=1.0)
    ball.visible_camera = False
    add_light(bpy, scene, "SUN", (0.0, 0.0, 5.0), (0.0, math.radians(-45.0), 0.0),
              energy=1.0, angle=math.radians(10.0))  # fmt: skip
    scene.whitted.shadow_samples = 16  # the wide sun's penumbra
    return scene


def _timed(bpy, scene, engine, **options):
    best = None
    for attempt in range(2):
        start = time.perf_counter()
        image = render_with(bpy, scene, engine, FOLDER / f"{engine}_{attempt}.exr", **options)
        seconds = time.perf_counter() - start
        if best is None or seconds < best[1]:
            best = (image.mean(axis=-1), seconds)
    return best


def _blocks(image):
    side = int(round(SQUARE / VIEW * SIZE))
    h = image.shape[0] // side
    return image[: h * side, : h * side].reshape(h, side, h, side).mean(axis=(1, 3))


def errors(image, reference):
    """(energy, peak, block RMS) relative errors against the reference."""
    energy = abs(image.mean() / reference.mean() - 1.0)
    blocks, ref_blocks = _blocks(image), _blocks(reference)
    peak = abs(blocks.max() / ref_blocks.max() - 1.0)
    rms = float(np.sqrt(np.mean((blocks - ref_blocks) ** 2)) / ref_blocks.mean())
    return energy, peak, rms


def main():
    import addon_utils

    addon_utils.enable("whitted", default_set=True)
    FOLDER.mkdir(exist_ok=True)
    scene = ball_lens(bpy)
    render_with(bpy, scene, "WHITTED", FOLDER / "warm.exr")  # the kernels, before any clock
    reference, reference_s = _timed(bpy, scene, "CYCLES", samples=REFERENCE, diffuse_bounces=1)
    print(f"cycles_reference_s: {reference_s:.1f}")
    rows, converged = [], {}

    def record(engine, label, image, seconds):
        energy, peak, rms = errors(image, reference)
        rows.append((f"{engine} (block RMS)", label, seconds, max(rms, 1e-4)))
        print(f"{engine} {label}: {seconds:.2f} s, energy {energy:.4f}, peak {peak:.4f}, "
              f"blocks {rms:.4f}")  # fmt: skip
        if engine not in converged and energy < 0.02 and peak < 0.2 and rms < BLOCK_TARGET:
            converged[engine] = seconds

    for samples in SAMPLES:
        image, seconds = _timed(bpy, scene, "CYCLES", samples=samples, diffuse_bounces=1)
        record("Cycles", samples, image, seconds)
    for photons in PHOTONS:
        scene.whitted.use_auto_photons = False
        scene.whitted.caustic_photons = photons
        image, seconds = _timed(bpy, scene, "WHITTED")
        record("Whitted", photons // 1000, image, seconds)
    write_chart("caustics_cycles", "Wide-sun ball lens against Cycles at 4096 spp "
                "(labels: spp, k photons)", rows, ("Whitted (block RMS)", 200), "spp or k photons",
                "caustics_cycles", xlabel="whole render time (s), 200 x 200",
                ylabel="0.2 m blocks' RMS error / mean")  # fmt: skip
    for engine in ("Cycles", "Whitted"):
        value = f"{converged[engine]:.2f}" if engine in converged else "not reached"
        print(f"{engine.lower()}_converged_s: {value}")
    if len(converged) == 2:
        print(f"cycles_over_whitted_converged: {converged['Cycles'] / converged['Whitted']:.1f}")


if __name__ == "__main__":
    main()
