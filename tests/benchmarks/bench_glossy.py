"""Chart 7 of speed against accuracy: rough mirrors and glass. A rough metal ball
(roughness 0.35) and a rough glass ball (0.25) on a checkered floor lit by a sun, under
tests/support/skies.py's sky without its sun (seen in the balls, lighting nothing), 64 x 64,
one camera ray through each pixel's centre; the error is the RMSE against a converged
render (4,096 glossy rays at each camera ray's hit). Nothing else in the picture is sampled,
so the error is the glossy rays' alone.

The sharp rule (glossy samples 0, the default: each rough surface reflects and refracts as
much light as its lobe on average, unblurred) against 1 to 1,024 glossy rays. Writes
results/glossy.png and .csv; prints glossy_default_rmse and _s (the sharp rule's), and
glossy_rays_to_beat_sharp: the fewest glossy rays whose error is below the sharp rule's,
with its time over the sharp rule's as glossy_cost_to_beat_sharp; and glossy_knee_rays,
where the error against time bends (`knee`)."""

import numpy as np

from core import (
    Box,
    Camera,
    Environment,
    Link,
    Material,
    RenderSettings,
    Scene,
    ShaderNode,
    Sphere,
    SunLight,
    Texture,
)
from tests.benchmarks.bench_sampling import timed_render, write_chart
from tests.support.skies import sky

SIZE = 64
GLOSSY = (0, 1, 2, 4, 8, 16, 64, 256, 1024)


def glossy_scene() -> Scene:
    checker = ShaderNode("checker", {"Color1": (0.9, 0.9, 0.9), "Color2": (0.1, 0.1, 0.1),
                                     "Scale": 8.0})  # fmt: skip
    floor = Box("Floor", Material(surface=ShaderNode(
        "diffuse", {"Color": Link(checker, "Color")})), np.diag([6.0, 6.0, 0.2, 1.0]))  # fmt: skip
    floor.world_from_object[2, 3] = -1.1
    metal = Material(surface=ShaderNode("principled", {
        "Base Color": (0.95, 0.7, 0.4), "Metallic": 1.0, "Roughness": 0.35}))  # fmt: skip
    glass = Material(surface=ShaderNode("glass", {"Roughness": 0.25, "IOR": 1.45}))
    left, right = np.eye(4), np.eye(4)
    left[0, 3], right[0, 3] = -1.1, 1.1
    camera = Camera(eye=(0.0, -6.0, 2.0), view=(0.0, 6.0, -2.0), up=(0.0, 0.0, 1.0), fovy=40.0)
    sunless = np.minimum(sky(), 2.0)
    world = Environment(colour=(1.0, 1.0, 1.0), image=Texture(pixels=sunless, srgb=False))
    sun = SunLight(direction=(0.3, 0.2, -1.0), irradiance=(3.0, 3.0, 3.0))
    shapes = [floor, Sphere("Metal", metal, left), Sphere("Glass", glass, right)]
    return Scene(camera, shapes, [sun], environment=world)


def _settings(glossy, seed=0):
    return RenderSettings(SIZE, SIZE, pixel_samples=1, glossy_samples=glossy,
                          environment_samples=0, seed=seed)  # fmt: skip


def knee(rows) -> int:
    """The rays where the error against time bends: the point of the curve farthest below
    the chord from its first point to its last, both axes scaled to 0..1 (the "kneedle"
    rule). core.model.settings.DEFAULT_GLOSSY_SAMPLES is chosen from it."""
    seconds = np.array([r[2] for r in rows])
    errors = np.array([r[3] for r in rows])
    t = (seconds - seconds[0]) / (seconds[-1] - seconds[0])
    e = (errors - errors[-1]) / (errors[0] - errors[-1])
    return int(rows[int(np.argmax(1.0 - t - e))][1])


def main():
    scene = glossy_scene()
    converged, _ = timed_render(scene, _settings(4096, seed=99), runs=1)
    rows = []
    for n in GLOSSY:
        image, seconds = timed_render(scene, _settings(n), runs=3)
        rmse = float(np.sqrt(np.mean((image - converged) ** 2)))
        rows.append(("glossy rays at the hit", n, seconds, rmse))
    write_chart("glossy", "Rough mirrors and glass: error against time (labels: rays)", rows,
                ("glossy rays at the hit", 0), "rays", "glossy")  # fmt: skip
    print(f"glossy_knee_rays: {knee(rows[1:])}")
    sharp = rows[0]
    beating = [r for r in rows[1:] if r[3] < sharp[3]]
    print(f"glossy_rays_to_beat_sharp: {beating[0][1] if beating else 'none'}")
    if beating:
        print(f"glossy_cost_to_beat_sharp: {beating[0][2] / sharp[2]:.2f}")


if __name__ == "__main__":
    main()
