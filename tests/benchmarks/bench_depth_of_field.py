"""Chart 3 of speed against accuracy: depth of field. Three textured spheres at different
depths, focused on the middle one, rendered with 1 to 256 camera rays per pixel (each ray
through its own stratified cell of the lens) for each pixel pattern; the error is the RMSE
against a converged render of 4,096 rays per pixel (64 x 64, jittered). Writes
results/depth_of_field.png and .csv; prints dof_default_rmse and dof_default_s (the setting
of the depth_of_field sample: 6 x 6 jittered rays)."""

import numpy as np

from core import Camera, Material, PointLight, RenderSettings, Scene, Sphere, Texture, render
from tests.benchmarks.bench_sampling import timed_render, write_chart

SIZE = 64
# What the depth_of_field sample file uses: 6 x 6 jittered rays
DEFAULT = ("jittered", 36)


def three_spheres():
    y, x = np.mgrid[0:64, 0:128]
    checker = ((x // 8 + y // 8) % 2).astype(np.float32)
    pixels = np.stack([0.2 + 0.7 * checker, 0.3 + 0.4 * checker, 0.8 - 0.6 * checker], -1)
    material = Material((0.7, 0.7, 0.7), (0.3, 0.3, 0.3), 30.0, texture=Texture(pixels=pixels))
    shapes = []
    for i, (x0, depth) in enumerate(((-1.6, 6.0), (0.0, 10.0), (1.9, 15.0))):
        m = np.diag([1.0, 1.0, 1.0, 1.0])
        m[:3, 3] = (x0, depth, 0.0)
        shapes.append(Sphere(f"S{i}", material, m))
    camera = Camera(eye=(0.0, 0.0, 0.5), view=(0.0, 1.0, -0.05), up=(0.0, 0.0, 1.0), fovy=28.0,
                    aperture_radius=0.25, focal_distance=10.0)  # fmt: skip
    light = PointLight((4.0, -2.0, 8.0), (1.0, 1.0, 1.0), (1.0, 0.0, 0.0))
    return Scene(camera, shapes, [light], ambient=(0.15, 0.15, 0.15), background=(0.1,) * 3)


def main():
    scene = three_spheres()
    converged = render(scene, RenderSettings(SIZE, SIZE, pixel_samples=64,
                                             pixel_sampling="jittered", seed=99)).image  # fmt: skip
    converged = converged[..., :3].astype(float)
    rows = []
    for pattern in ("grid", "jittered", "random"):
        for n in (1, 2, 3, 4, 6, 8, 12, 16):
            settings = RenderSettings(SIZE, SIZE, pixel_samples=n, pixel_sampling=pattern)
            image, seconds = timed_render(scene, settings)
            rmse = float(np.sqrt(np.mean((image - converged) ** 2)))
            rows.append((pattern, n * n, seconds, rmse))
    write_chart("depth_of_field", "Depth of field: error against time (labels: rays)", rows,
                DEFAULT, "rays_per_pixel", "dof")  # fmt: skip


if __name__ == "__main__":
    main()
