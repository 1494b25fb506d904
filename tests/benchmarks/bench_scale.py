"""Scene-size benchmark: shapes and mesh instances cost what they should.

Renders grids of 100 and 10,000 analytic shapes, and of 100 and 10,000 instances of one
10,000-triangle mesh, at a fixed image size and camera framing, and prints the render time
ratios 10,000 / 100 (a BVH over the objects makes these a small factor, not 100; every pixel
sees a smaller object, so more silhouettes and more near misses), the packing time, and
the mesh bytes of 10,000 instances against one (instances share their triangles: 1.0).
"""

import time

import numpy as np

from core import (
    Camera,
    Material,
    Mesh,
    PointLight,
    RenderSettings,
    Scene,
    Sphere,
    Torus,
    TriangleMesh,
    render,
)
from core.compile import compile_scene
from tests.support.meshes import icosphere


def grid(count, make):
    side = int(round(np.sqrt(count)))
    spacing = 40.0 / side
    shapes = []
    for i in range(side):
        for j in range(side):
            m = np.diag([spacing * 0.35] * 3 + [1.0])
            m[:3, 3] = (-20 + (i + 0.5) * spacing, -20 + (j + 0.5) * spacing, 0.0)
            shapes.append(make(f"s{i}_{j}", m, i + j))
    camera = Camera(eye=(0, -30, 40), view=(0, 30, -40), up=(0, 0, 1), fovy=50)
    light = PointLight((10, -10, 50), (1, 1, 1), (1, 0, 0))
    return Scene(camera, shapes, [light], ambient=(0.1, 0.1, 0.1))


def seconds(scene, settings):
    """(tile rendering seconds, packing seconds): packing is Python per object, once."""
    render(scene, RenderSettings(8, 8, pixel_samples=1))  # kernels ready
    start = time.perf_counter()
    out = render(scene, settings)
    return out.stats.render_s, time.perf_counter() - start - out.stats.render_s - out.stats.kernel_s


def main():
    settings = RenderSettings(256, 192, pixel_samples=1)
    material = Material(diffuse=(0.7, 0.6, 0.5))

    def analytic(name, m, k):
        return Sphere(name, material, m) if k % 2 else Torus(name, material, m, 1.0, 0.3)

    small, large = grid(100, analytic), grid(10_000, analytic)
    (render_large, pack_large), (render_small, _) = (
        seconds(large, settings),
        seconds(small, settings),
    )
    print(f"analytic_10k_over_100_render_time_ratio: {render_large / render_small:.2f}")
    print(f"analytic_10k_pack_s: {pack_large:.2f}")

    vertices, triangles = icosphere(5)  # 20,480 triangles
    ball = TriangleMesh(vertices, triangles, smooth=True)

    def instance(name, m, k):
        return Mesh(name, material, m, ball)

    small, large = grid(100, instance), grid(10_000, instance)
    (render_large, pack_large), (render_small, _) = (
        seconds(large, settings),
        seconds(small, settings),
    )
    print(f"instances_10k_over_100_render_time_ratio: {render_large / render_small:.2f}")
    print(f"instances_10k_pack_s: {pack_large:.2f}")
    one = compile_scene(Scene(shapes=large.shapes[:1]), settings).mesh_bytes
    many = compile_scene(large, settings).mesh_bytes
    print(f"instances_10k_mesh_bytes_over_one: {many / one:.2f}")
    print(f"triangles_seen_by_10k_instances: {len(triangles) * 10_000}")


if __name__ == "__main__":
    main()
