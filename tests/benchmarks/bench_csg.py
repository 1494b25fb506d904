"""CSG benchmark: the report's three CSG examples and a mug (cylinder minus cylinder) on a
textured floor.

Prints, per example, the render time of one 256x256 frame and camera rays per second, and
csg_cost_ratio: the time of tracing camera rays against the CSG solid divided by the sum of
the times against each of its operands alone (same rays, same process, best of 5); the
target is at most 2. Writes results/csg.csv and csg.png.
"""

import time
from pathlib import Path

import numpy as np

from core import (
    Box,
    Camera,
    Csg,
    Cylinder,
    Material,
    PointLight,
    RenderSettings,
    Scene,
    Texture,
    render,
)
from core.compile import pack_scene
from core.kernels.batch import closest_hits
from core.kernels.workspace import new_workspace
from tests.support.csg_examples import EXAMPLES, analytic_tree, scaled

RESULTS = Path(__file__).resolve().parent / "results"
SIZE = 256


def mug():
    """A mug: an outer cylinder minus an inner one that stops short of the bottom."""
    clay = Material((0.8, 0.75, 0.6), (0.3, 0.3, 0.3), 40)
    outer = Cylinder("Outer", clay, scaled(0.8, 0.8, 1.0))
    inner_m = scaled(0.7, 0.7, 1.0)
    inner_m[2, 3] = 0.15
    inner = Cylinder("Inner", clay, inner_m)
    return Csg("Mug", operation="difference", left=outer, right=inner)


def checker_floor():
    cells = (np.indices((64, 64)).sum(axis=0) // 8) % 2
    pixels = np.where(cells[..., None] == 1, (0.9, 0.9, 0.9), (0.2, 0.25, 0.3))
    floor_m = scaled(6.0, 6.0, 0.05)
    floor_m[2, 3] = -1.6
    return Box("Floor", Material((1, 1, 1), texture=Texture(pixels=pixels)), floor_m)


def operands(node, out):
    if isinstance(node, Csg):
        for operand in (node.left, node.right):
            operands(operand, out)
    else:
        out.append(node)
    return out


def with_world(node, world):
    """The operand placed by `world` (its CSG ancestors' transforms, here all identity)."""
    return type(node)(node.name, node.material, world @ node.world_from_object)


def camera():
    return Camera((3.2, -4.4, 2.6), (-3.2, 4.4, -2.9), (0, 0, 1.0), 40)


def camera_rays(size):
    cam = camera()
    forward = np.asarray(cam.view, float) / np.linalg.norm(cam.view)
    right = np.cross(forward, cam.up)
    right /= np.linalg.norm(right)
    up = np.cross(right, forward)
    half = np.tan(np.radians(cam.fovy) / 2)
    s = np.linspace(-half, half, size)
    x, y = np.meshgrid(s, -s)
    d = (forward + x[..., None] * right + y[..., None] * up).reshape(-1, 3)
    d /= np.linalg.norm(d, axis=1, keepdims=True)
    return np.broadcast_to(np.asarray(cam.eye, float), d.shape).copy(), d


def trace_seconds(shapes, origins, directions, repeats=5):
    geometry = pack_scene(Scene(shapes=shapes), RenderSettings(8, 8, pixel_samples=1)).geometry
    stacks = new_workspace(0).stacks
    n = len(origins)
    out = np.empty(n), np.empty(n, np.int64), np.empty(n, np.int64)
    closest_hits(geometry, origins[:10], directions[:10], np.inf, *(o[:10] for o in out), stacks)
    best = np.inf
    for _ in range(repeats):
        start = time.perf_counter()
        closest_hits(geometry, origins, directions, np.inf, *out, stacks)
        best = min(best, time.perf_counter() - start)
    return best


def main():
    solids = {name: analytic_tree(first, steps) for name, first, steps in EXAMPLES}
    solids["mug"] = mug()
    light = PointLight((4.0, -3.0, 6.0), (1.0, 1.0, 1.0))
    origins, directions = camera_rays(SIZE)
    render(
        Scene(camera(), [solids["mug"], checker_floor()], [light]),
        RenderSettings(8, 8, pixel_samples=1),
    )
    rows = []
    for name, solid in solids.items():
        scene = Scene(camera(), [solid, checker_floor()], [light], ambient=(0.1, 0.1, 0.1))
        frame = min(
            _timed(lambda scene=scene: render(scene, RenderSettings(SIZE, SIZE, pixel_samples=1)))
            for _ in range(3)
        )
        csg_s = trace_seconds([solid], origins, directions)
        parts = [with_world(op, np.eye(4)) for op in operands(solid, [])]
        parts_s = sum(trace_seconds([part], origins, directions) for part in parts)
        ratio = csg_s / parts_s
        print(f"csg_{name}_frame_s: {frame:.4f}")
        print(f"csg_{name}_camera_mrays_per_s: {SIZE * SIZE / frame / 1e6:.3f}")
        print(f"csg_{name}_cost_ratio: {ratio:.2f} ({len(parts)} operands)")
        rows.append((name, frame, csg_s, parts_s, ratio))
    print(f"csg_examples_s: {sum(r[1] for r in rows):.4f}")
    print(f"csg_cost_ratio: {max(r[4] for r in rows):.2f} (worst example)")
    write_results(rows)


def _timed(f):
    start = time.perf_counter()
    f()
    return time.perf_counter() - start


def write_results(rows):
    RESULTS.mkdir(exist_ok=True)
    with open(RESULTS / "csg.csv", "w") as f:
        f.write("example,frame_s,csg_trace_s,operands_trace_s,cost_ratio\n")
        f.writelines(f"{n},{a:.6f},{b:.6f},{c:.6f},{r:.4f}\n" for n, a, b, c, r in rows)
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(6, 3.5))
    x = np.arange(len(rows))
    ax.bar(x - 0.2, [r[2] * 1e3 for r in rows], 0.4, label="CSG solid")
    ax.bar(x + 0.2, [r[3] * 1e3 for r in rows], 0.4, label="its operands, each alone, summed")
    ax.set_xticks(x, [r[0] for r in rows])
    ax.set_ylabel(f"ms for {SIZE}x{SIZE} camera rays")
    ax.set_title("CSG cost against its operands' (target: at most 2x)")
    ax.legend()
    fig.tight_layout()
    fig.savefig(RESULTS / "csg.png", dpi=100)
    print(f"chart: {RESULTS / 'csg.png'}")


if __name__ == "__main__":
    main()
