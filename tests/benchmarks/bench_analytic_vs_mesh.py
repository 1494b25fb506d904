"""Chart 4 of speed against accuracy: analytic shapes against tessellated ones.

The sphere, cylinder, cone and torus, each rendered as the exact shape Whitted exports for a
tagged object and as smooth-shaded meshes of 32 to 1,000,000 triangles (tessellation.py),
seen from one oblique camera. For each:

- silhouette error: the area between the rendered outline and the exact one, over the exact
  outline's area. The exact outline comes from ray-shape intersection in numpy (the torus's
  quartic by companion-matrix eigenvalues, Newton-polished), written apart from the kernels.
  Rays first sample 4 x 4 points per pixel; where either outline passes (pixels either sees
  partly covered, and their neighbours) they sample 32 x 32 points, so outlines a
  thousandth of a pixel apart still register.
- normal error: the mean angle between the shading normal the renderer uses (the kernels'
  `closest_normals`) and the exact normal where the exact shape is hit, over pixel centres
  both hit.
- render time of a 512 x 512 frame (one point light with its shadow, warm kernels, one
  thread, best of 5) and the bytes of the packed geometry; the BVH build is timed apart.

Prints analytic_vs_mesh_speedup (render time of the 1,000,000-triangle cylinder over the
exact one), instanced_bytes_per_triangle (1,000 instances of one 100,000-triangle mesh: all
packed geometry bytes over the 100 million triangles rendered) and the figures behind them.
Writes results/analytic_vs_mesh.png and .csv.
"""

import csv
import math
import time
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from core import (  # noqa: E402
    Camera,
    Cone,
    Cylinder,
    Material,
    Mesh,
    PointLight,
    RenderSettings,
    Scene,
    Sphere,
    Torus,
    render,
)  # fmt: skip
from core.compile import compile_scene  # noqa: E402
from core.kernels.batch import closest_normals  # noqa: E402
from core.kernels.workspace import new_workspace  # noqa: E402
from tests.benchmarks.bench_sampling import timed_render  # noqa: E402
from tests.benchmarks.tessellation import TORUS_MAJOR, TORUS_MINOR, tessellate  # noqa: E402

RESULTS = Path(__file__).resolve().parent / "results"
SIZE = 256  # the error's image
TIMED_SIZE = 512  # the timed render's: big enough that tracing, not set-up, dominates
EYE = np.array([2.8, -3.6, 2.4])
FOVY = 36.0
COARSE, FINE = 4, 32  # sample points per pixel side
TRIANGLES = [32, 128, 512, 2_048, 8_192, 32_768, 131_072, 524_288, 1_000_000]
KINDS = ("sphere", "cylinder", "cone", "torus")
MATERIAL = Material((0.7, 0.5, 0.3), (0.4, 0.4, 0.4), 25.0)


# --- rays and the exact shapes in numpy ---------------------------------------------------
def camera_frame():
    forward = -EYE / np.linalg.norm(EYE)
    right = np.cross(forward, (0.0, 0.0, 1.0))
    right /= np.linalg.norm(right)
    return forward, right, np.cross(right, forward)


def pixel_rays(rows, cols, per_side):
    """Unit directions (len(rows), per_side^2, 3) through a per_side^2 grid in each listed
    pixel of the SIZE x SIZE image, row 0 at the top."""
    forward, right, up = camera_frame()
    half = math.tan(math.radians(FOVY) / 2.0)
    offsets = (np.arange(per_side) + 0.5) / per_side
    fy, fx = (a.ravel() for a in np.meshgrid(offsets, offsets, indexing="ij"))
    x = ((cols[:, None] + fx[None, :]) / SIZE * 2.0 - 1.0) * half
    y = (1.0 - (rows[:, None] + fy[None, :]) / SIZE * 2.0) * half
    d = forward + x[..., None] * right + y[..., None] * up
    return d / np.linalg.norm(d, axis=-1, keepdims=True)


def _nearest(candidates):
    """(hit, t, normal) from the candidate (t, normal) pairs, t = inf where invalid."""
    ts = np.stack([t for t, _ in candidates])
    ts[~(ts > 1e-9)] = np.inf
    pick = np.argmin(ts, axis=0)
    rows = np.arange(ts.shape[1])
    normals = np.stack([n for _, n in candidates])[pick, rows]
    t = ts[pick, rows]
    with np.errstate(invalid="ignore", divide="ignore"):
        return np.isfinite(t), t, normals / np.linalg.norm(normals, axis=-1, keepdims=True)


def _quadratic(a, b, c):
    """Both roots of a t^2 + 2 b t + c, NaN where there are none."""
    with np.errstate(invalid="ignore", divide="ignore"):
        root = np.sqrt(b * b - a * c)
        return (-b - root) / a, (-b + root) / a


def _cap(d, z, facing):
    with np.errstate(invalid="ignore", divide="ignore"):
        t = (z - EYE[2]) / d[:, 2]
    p = EYE + t[:, None] * d
    t = np.where(p[:, 0] ** 2 + p[:, 1] ** 2 <= 1.0, t, np.inf)
    return t, np.broadcast_to([0.0, 0.0, facing], d.shape)


def _on_side(d, t, z_ok, normal_of):
    p = EYE + t[:, None] * d
    return np.where(z_ok(p[:, 2]), t, np.inf), normal_of(p)


def exact_sphere(d):
    b, c = d @ EYE, EYE @ EYE - 1.0
    return [(t, EYE + t[:, None] * d) for t in _quadratic(np.ones(len(d)), b, c)]


def exact_cylinder(d):
    a = d[:, 0] ** 2 + d[:, 1] ** 2
    b, c = d[:, :2] @ EYE[:2], EYE[:2] @ EYE[:2] - 1.0
    side = [
        _on_side(d, t, lambda z: np.abs(z) <= 1.0, lambda p: p * [1.0, 1.0, 0.0])
        for t in _quadratic(a, b, c)
    ]
    return side + [_cap(d, 1.0, 1.0), _cap(d, -1.0, -1.0)]


def exact_cone(d):
    # x^2 + y^2 = w^2 with w = (1 - z) / 2 = w0 + t wd, for w in [0, 1]
    w0, wd = (1.0 - EYE[2]) / 2.0, -d[:, 2] / 2.0
    a = d[:, 0] ** 2 + d[:, 1] ** 2 - wd * wd
    b = d[:, :2] @ EYE[:2] - w0 * wd
    c = EYE[:2] @ EYE[:2] - w0 * w0

    def normal(p):
        return np.column_stack([2.0 * p[:, 0], 2.0 * p[:, 1], (1.0 - p[:, 2]) / 2.0])

    side = [_on_side(d, t, lambda z: np.abs(z) <= 1.0, normal) for t in _quadratic(a, b, c)]
    return side + [_cap(d, -1.0, -1.0)]


def _horner(coeffs, t):
    """Each ray's polynomial (coefficients highest first, a row per ray) at its roots t."""
    value = np.zeros_like(t)
    for j in range(coeffs.shape[1]):
        value = value * t + coeffs[:, j : j + 1]
    return value


def exact_torus(d, chunk=200_000):
    """Real roots of (|p|^2 + R^2 - r^2)^2 = 4 R^2 (x^2 + y^2) along each ray: eigenvalues of
    the quartic's companion matrix, then Newton steps in float64 on the real ones."""
    big2, small2 = TORUS_MAJOR**2, TORUS_MINOR**2
    od, oo = d @ EYE, EYE @ EYE
    k = oo + big2 - small2
    exy = d[:, 0] ** 2 + d[:, 1] ** 2
    fxy = 2.0 * (d[:, :2] @ EYE[:2])
    gxy = EYE[:2] @ EYE[:2]
    coeffs = np.column_stack([  # t^4 (|d| = 1) down to t^0
        np.ones(len(d)), 4.0 * od, 4.0 * od * od + 2.0 * k - 4.0 * big2 * exy,
        4.0 * od * k - 4.0 * big2 * fxy, np.full(len(d), k * k - 4.0 * big2 * gxy),
    ])  # fmt: skip
    roots = np.empty((len(d), 4), complex)
    for s in range(0, len(d), chunk):
        c = coeffs[s : s + chunk]
        companion = np.zeros((len(c), 4, 4))
        companion[:, 0, :] = -c[:, 1:]
        companion[:, 1, 0] = companion[:, 2, 1] = companion[:, 3, 2] = 1.0
        roots[s : s + chunk] = np.linalg.eigvals(companion)
    t = np.where(np.abs(roots.imag) < 1e-6, roots.real, np.nan)
    slope_coeffs = coeffs[:, :-1] * [4.0, 3.0, 2.0, 1.0]
    for _ in range(3):
        value, slope = _horner(coeffs, t), _horner(slope_coeffs, t)
        with np.errstate(invalid="ignore", divide="ignore"):
            step = np.where(slope != 0.0, value / slope, 0.0)
        t = t - np.where(np.abs(step) < 1e-3, step, 0.0)

    def normal(p):
        s = np.sum(p * p, axis=1, keepdims=True) + big2 - small2
        return 4.0 * s * p - 8.0 * big2 * p * [1.0, 1.0, 0.0]

    return [(ti, normal(EYE + np.nan_to_num(ti)[:, None] * d)) for ti in t.T]


EXACT = {"sphere": exact_sphere, "cylinder": exact_cylinder, "cone": exact_cone,
         "torus": exact_torus}  # fmt: skip


def exact_hits(kind, d):
    return _nearest([(np.where(np.isnan(t), np.inf, t), n) for t, n in EXACT[kind](d)])


# --- the renderer's view of one shape -----------------------------------------------------
def traced(packed, d, stacks):
    """(hit, shading normal) of the renderer for rays from EYE along d (n, 3)."""
    n = len(d)
    t, shape, normal = np.empty(n), np.empty(n, np.int64), np.empty((n, 3))
    origins = np.broadcast_to(EYE, d.shape).copy()
    closest_normals(packed.geometry, packed.surfaces, origins, np.ascontiguousarray(d),
                    math.inf, t, shape, normal, stacks)  # fmt: skip
    return shape >= 0, normal


def _partly_covered(hits):
    """Pixels (SIZE, SIZE) whose samples (the last axis) are neither all hits nor all misses."""
    return hits.any(-1) & ~hits.all(-1)


def silhouette_error(kind, packed, stacks, coarse_exact):
    """Area between the renderer's outline and the exact one, over the exact area. Pixels
    whose coarse samples all agree in each image count whole (fully in one and out of the
    other, or equal); the band where either outline passes is sampled finely."""
    rows, cols = (a.ravel() for a in np.mgrid[0:SIZE, 0:SIZE])
    d = pixel_rays(rows, cols, COARSE).reshape(-1, 3)
    ours = traced(packed, d, stacks)[0].reshape(SIZE, SIZE, -1)
    padded = np.pad(_partly_covered(ours) | _partly_covered(coarse_exact), 1)
    band = np.zeros((SIZE, SIZE), bool)
    for dy in (0, 1, 2):
        for dx in (0, 1, 2):
            band |= padded[dy : dy + SIZE, dx : dx + SIZE]
    whole = np.count_nonzero(~band & (ours[..., 0] != coarse_exact[..., 0]))
    differ = 0
    rows, cols = np.nonzero(band)
    for start in range(0, len(rows), 2048):  # in pieces, to bound memory
        d = pixel_rays(rows[start : start + 2048], cols[start : start + 2048], FINE)
        d = d.reshape(-1, 3)
        differ += np.count_nonzero(traced(packed, d, stacks)[0] != exact_hits(kind, d)[0])
    area = coarse_exact.sum() / COARSE**2
    return (whole + differ / FINE**2) / area


def normal_error(kind, packed, stacks):
    rows, cols = (a.ravel() for a in np.mgrid[0:SIZE, 0:SIZE])
    d = pixel_rays(rows, cols, 1).reshape(-1, 3)
    hit, _, exact = exact_hits(kind, d)
    ours_hit, ours = traced(packed, d, stacks)
    both = hit & ours_hit
    cosine = np.clip(np.sum(ours[both] * exact[both], axis=1), -1.0, 1.0)
    return float(np.degrees(np.arccos(cosine)).mean())


def geometry_bytes(packed):
    return sum(a.nbytes for group in (packed.geometry, packed.surfaces) for a in group)


def analytic(kind):
    shape = {"sphere": Sphere, "cylinder": Cylinder, "cone": Cone}.get(kind)
    if shape is None:
        return Torus(kind, MATERIAL, major_radius=TORUS_MAJOR, minor_radius=TORUS_MINOR)
    return shape(kind, MATERIAL)


def one_shape_scene(shape):
    camera = Camera(eye=tuple(EYE), view=tuple(-EYE), up=(0.0, 0.0, 1.0), fovy=FOVY)
    light = PointLight((4.0, -5.0, 6.0), (1.0, 1.0, 1.0), (1.0, 0.0, 0.0))
    return Scene(camera, [shape], [light], ambient=(0.1, 0.1, 0.1))


def measure(kind, shape, coarse_exact, stacks, triangles):
    scene = one_shape_scene(shape)
    # One thread: the differences are tens of milliseconds, and thread scheduling blurs them
    settings = RenderSettings(TIMED_SIZE, TIMED_SIZE, pixel_samples=1, threads=1)
    start = time.perf_counter()
    compiled = compile_scene(scene, settings)
    build_s = time.perf_counter() - start
    packed = compiled.packed
    _, render_s = timed_render(scene, settings, runs=5)
    return {
        "shape": kind,
        "triangles": triangles,
        "render_s": render_s,
        "build_s": build_s,
        "bytes": geometry_bytes(packed),
        "silhouette_error": silhouette_error(kind, packed, stacks, coarse_exact),
        "normal_error_deg": normal_error(kind, packed, stacks),
    }


def chart(rows):
    RESULTS.mkdir(exist_ok=True)
    with open(RESULTS / "analytic_vs_mesh.csv", "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=list(rows[0]))
        writer.writeheader()
        writer.writerows(rows)
    fig, axes = plt.subplots(2, 2, figsize=(11, 8.5))
    floor = {"silhouette_error": 1e-9, "normal_error_deg": 1e-9}
    for kind, colour in zip(KINDS, ("C0", "C1", "C2", "C3"), strict=True):
        mesh = [r for r in rows if r["shape"] == kind and r["triangles"]]
        exact = next(r for r in rows if r["shape"] == kind and not r["triangles"])
        for (y, ylabel), ax_row in zip(
            (("silhouette_error", "silhouette error (area off / area)"),
             ("normal_error_deg", "mean normal error (degrees)")), axes, strict=True,
        ):  # fmt: skip
            for x, ax in zip(("render_s", "bytes"), ax_row, strict=True):
                ax.plot([r[x] for r in mesh], [max(r[y], floor[y]) for r in mesh], "o-",
                        color=colour, label=f"{kind} mesh", markersize=4)  # fmt: skip
                ax.plot(exact[x], max(exact[y], floor[y]), "*", color=colour, markersize=14,
                        markeredgecolor="k", label=f"{kind} exact (default)")  # fmt: skip
                if kind == "cylinder":
                    for r in mesh:
                        where = (r[x], max(r[y], floor[y]))
                        ax.annotate(f"{r['triangles']:,}", where, fontsize=6, xytext=(3, 3),
                                    textcoords="offset points")  # fmt: skip
                ax.set_xscale("log")
                ax.set_yscale("log")
                ax.xaxis.set_minor_formatter(matplotlib.ticker.NullFormatter())
                ax.set_ylabel(ylabel)
                ax.set_xlabel("render time (s), 512 x 512" if x == "render_s"
                              else "packed geometry (bytes)")  # fmt: skip
                ax.grid(True, which="both", alpha=0.3)
    axes[0, 0].legend(fontsize=7, ncol=2)
    title = "Analytic shapes against meshes of 32 to 1,000,000 triangles"
    fig.suptitle(f"{title} (labels: cylinder triangles; a star on the floor: no error)")
    fig.tight_layout()
    fig.savefig(RESULTS / "analytic_vs_mesh.png", dpi=120)
    plt.close(fig)


def instancing():
    """Bytes per rendered triangle for 1,000 instances of one 100,000-triangle mesh."""
    mesh = tessellate("torus", 100_000)
    rng = np.random.default_rng(3)
    shapes = []
    for i, (x, y, z) in enumerate(np.ndindex(10, 10, 10)):
        q, r = np.linalg.qr(rng.normal(size=(3, 3)))
        m = np.eye(4)
        m[:3, :3] = q * np.sign(np.diag(r)) * np.sign(np.linalg.det(q))  # a random rotation
        m[:3, 3] = (3.0 * x, 3.0 * y, 3.0 * z)
        shapes.append(Mesh(f"Torus {i}", MATERIAL, m, mesh=mesh))
    camera = Camera(eye=(-14.0, -22.0, 40.0), view=(27.5, 35.5, -26.5), up=(0.0, 0.0, 1.0),
                    fovy=45.0)  # fmt: skip
    light = PointLight((-10.0, -20.0, 60.0), (1.0, 1.0, 1.0), (1.0, 0.0, 0.0))
    scene = Scene(camera, shapes, [light], ambient=(0.1, 0.1, 0.1))
    settings = RenderSettings(SIZE, SIZE, pixel_samples=1)
    start = time.perf_counter()
    compiled = compile_scene(scene, settings)
    build_s = time.perf_counter() - start
    image, render_s = timed_render(scene, settings, runs=2)
    rendered = len(shapes) * compiled.triangles
    covered = float(np.mean(image.max(axis=-1) > 0.0))
    return (
        geometry_bytes(compiled.packed),
        rendered,
        compiled.mesh_bytes,
        build_s,
        render_s,
        covered,
    )


def main():
    stacks = new_workspace(0).stacks
    render(one_shape_scene(analytic("sphere")), RenderSettings(4, 4))  # load the kernels
    rows = []
    for kind in KINDS:
        rows_, cols_ = (a.ravel() for a in np.mgrid[0:SIZE, 0:SIZE])
        coarse = exact_hits(kind, pixel_rays(rows_, cols_, COARSE).reshape(-1, 3))[0]
        coarse = coarse.reshape(SIZE, SIZE, -1)
        rows.append(measure(kind, analytic(kind), coarse, stacks, 0))
        for count in TRIANGLES:
            mesh = tessellate(kind, count)
            shape = Mesh(f"{kind} mesh", MATERIAL, np.eye(4), mesh=mesh)
            rows.append(measure(kind, shape, coarse, stacks, len(mesh.triangles)))
        for r in rows:
            if r["shape"] == kind:
                print(f"  {kind:>8} {r['triangles']:>9,} tris  render {r['render_s']:.4f} s  "
                      f"build {r['build_s']:.3f} s  {r['bytes']:>11,} B  silhouette "
                      f"{r['silhouette_error']:.2e}  normal {r['normal_error_deg']:.2e} deg",
                      flush=True)  # fmt: skip
    chart(rows)
    exact = next(r for r in rows if r["shape"] == "cylinder" and not r["triangles"])
    biggest = max((r for r in rows if r["shape"] == "cylinder"), key=lambda r: r["triangles"])
    print(f"analytic_vs_mesh_speedup: {biggest['render_s'] / exact['render_s']:.2f}")
    print(f"  (cylinder of {biggest['triangles']:,} triangles: {biggest['render_s']:.4f} s, "
          f"{biggest['bytes']:,} B; exact: {exact['render_s']:.4f} s, "
          f"{exact['bytes']:,} B)")  # fmt: skip
    total, rendered, mesh_bytes, build_s, render_s, covered = instancing()
    print(f"instanced_bytes_per_triangle: {total / rendered:.4f}")
    print(f"  (1,000 instances, {rendered:,} triangles in {total:,} B; the shared mesh alone "
          f"{mesh_bytes:,} B; build {build_s:.2f} s; render {render_s:.3f} s; "
          f"{covered:.0%} of pixels covered)")  # fmt: skip


if __name__ == "__main__":
    main()
