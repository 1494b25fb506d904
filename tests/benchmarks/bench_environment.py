"""Chart 6 of speed against accuracy: light from an environment image (an HDRI World). A ball
and a box on a plane under tests/support/skies.py's sky (a bright 3 x 3-pixel sun in a
gradient), 64 x 64, one camera ray per pixel, rendered with 1 to 256 shadow rays towards the
environment per shading point in each shadow pattern; the error is the RMSE against a
converged render (4,096 rays). Writes results/environment.png and .csv; prints
environment_default_rmse and _s (the default World Samples, 16, stratified),
environment_default_relative_rmse (over the picture's mean), and environment_cost_ratio: the
default's render time over the same scene's with a black World (camera rays alone)."""

import numpy as np

from core import Box, Camera, Environment, Material, RenderSettings, Scene, Sphere, Texture
from core.model.settings import DEFAULT_ENVIRONMENT_SAMPLES
from tests.benchmarks.bench_sampling import timed_render, write_chart
from tests.support.skies import sky

SIZE = 64
COUNTS = (1, 2, 4, 8, 16, 32, 64, 128, 256)


def hdri_scene(lit: bool = True) -> Scene:
    white = Material(diffuse=(0.8, 0.8, 0.8))
    ground = Box("Ground", white, np.diag([20.0, 20.0, 1.0, 1.0]))
    ground.world_from_object[2, 3] = -1.0
    ball = Sphere("Ball", Material(diffuse=(0.8, 0.3, 0.2)), np.eye(4))
    ball.world_from_object[:3, 3] = (0.6, 0.4, 1.0)
    box = Box("Box", white, np.diag([0.6, 0.6, 0.6, 1.0]))
    box.world_from_object[:3, 3] = (-1.0, -0.6, 0.6)
    camera = Camera(eye=(0.0, -7.0, 4.0), view=(0.0, 7.0, -3.2), up=(0.0, 0.0, 1.0), fovy=40.0)
    environment = None
    if lit:
        image = Texture(pixels=sky(), srgb=False)
        environment = Environment(colour=(1.0, 1.0, 1.0), image=image)
    return Scene(camera, [ground, ball, box], environment=environment)


def main():
    scene = hdri_scene()
    converged, _ = timed_render(scene, RenderSettings(SIZE, SIZE, pixel_samples=1,
                                environment_samples=4096, seed=99), runs=1)  # fmt: skip
    rows, mean = [], float(converged.mean())
    for pattern in ("stratified", "halton", "uniform"):
        for n in COUNTS:
            settings = RenderSettings(SIZE, SIZE, pixel_samples=1, environment_samples=n,
                                      shadow_sampling=pattern)  # fmt: skip
            image, seconds = timed_render(scene, settings)
            rmse = float(np.sqrt(np.mean((image - converged) ** 2)))
            rows.append((pattern, n, seconds, rmse))
    write_chart("environment", "Environment light: error against time (labels: rays)", rows,
                ("stratified", DEFAULT_ENVIRONMENT_SAMPLES), "environment_rays",
                "environment")  # fmt: skip
    default = next(r for r in rows if r[:2] == ("stratified", DEFAULT_ENVIRONMENT_SAMPLES))
    print(f"environment_default_relative_rmse: {default[3] / mean:.3f}")
    # What the World's light costs: the default against a black World, interleaved
    settings = RenderSettings(SIZE * 2, SIZE * 2)
    lit, dark = [], []
    for _ in range(3):
        lit.append(timed_render(scene, settings, runs=1)[1])
        dark.append(timed_render(hdri_scene(lit=False), settings, runs=1)[1])
    print(f"environment_cost_ratio: {np.median(lit) / np.median(dark):.2f}")


if __name__ == "__main__":
    main()
