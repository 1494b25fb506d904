"""Charts 1 and 2 of speed against accuracy: anti-aliasing patterns and soft-shadow
patterns, each against an exact answer computed here in numpy, outside the renderer.

1. Anti-aliasing: a box turned 20° about the view axis and a sphere, white (ambient 1, no
   lights) on black, so a pixel's exact value is the fraction of it the shapes cover. The
   reference casts 64 x 64 rays per pixel at the two shapes in numpy. Patterns: "grid" (the
   report's n x n), "jittered", "random"; 1 to 256 samples per pixel.
2. Soft shadows: a floor under a 2 x 1.5 rectangular light with a box between them; the
   floor's exact irradiance is the light's integral of cos(theta) minus that integral over
   the box's shadow polygon on the light (the box's corners projected from the floor point,
   their convex hull clipped to the light), each by Gauss quadrature. Patterns: "uniform"
   (the report's), "stratified", "halton"; 1 to 256 shadow rays, at one camera ray per
   pixel; and the default pattern under the default 3 x 3 camera rays, against the mean of
   the exact irradiance at the pixel's nine grid points: what a default render gets.

Error is the RMSE over the image (floor pixels for chart 2); time is render time in this
process, best of 5, kernels already loaded. Writes results/antialiasing.png, shadows.png
and their CSVs; prints aa_default_rmse, aa_default_s, shadow_default_rmse, shadow_default_s.
"""

import csv
import math
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from core import AreaLight, Box, Camera, Material, RenderSettings, Scene, Sphere, render  # noqa: E402

RESULTS = Path(__file__).resolve().parent / "results"
SIZE = 64
FOVY = 20.0
EYE_HEIGHT = 10.0
TURN = math.radians(20.0)
# Each chart's default: what RenderSettings and the Blender panel start with
AA_DEFAULT = (RenderSettings.pixel_sampling, RenderSettings.pixel_samples)
SHADOW_DEFAULT = (RenderSettings.shadow_sampling, RenderSettings.shadow_samples)


def look_down():
    return Camera(eye=(0.0, 0.0, EYE_HEIGHT), view=(0.0, 0.0, -1.0), up=(0.0, 1.0, 0.0),
                  fovy=FOVY)  # fmt: skip


def pixel_rays(per_side):
    """Unit directions (SIZE, SIZE, per_side^2, 3) through a per_side^2 grid in each pixel
    of the look_down camera, row 0 at the top."""
    half = math.tan(math.radians(FOVY) / 2.0)
    offsets = (np.arange(per_side) + 0.5) / per_side
    cells = np.arange(SIZE)
    u = (cells[:, None] + offsets[None, :]).reshape(-1) / SIZE * 2.0 - 1.0  # x, left to right
    x = np.repeat(u.reshape(SIZE, per_side), per_side, axis=1)  # (col, per_side^2)
    y = np.tile(-u.reshape(SIZE, per_side), (1, per_side))  # (row, per_side^2), top first
    d = np.empty((SIZE, SIZE, per_side * per_side, 3))
    d[..., 0] = half * x[None, :, :]
    d[..., 1] = half * y[:, None, :]
    d[..., 2] = -1.0
    return d / np.linalg.norm(d, axis=-1, keepdims=True)


# --- chart 1: anti-aliasing ---------------------------------------------------------------
BOX_HALF = np.array([0.9, 0.6, 0.1])
BOX_CENTRE = np.array([-0.7, 0.2, 0.0])
SPHERE_CENTRE, SPHERE_RADIUS = np.array([0.95, -0.4, 0.0]), 0.55


def edge_scene():
    white = Material((1.0, 1.0, 1.0))
    turn = np.eye(4)
    c, s = math.cos(TURN), math.sin(TURN)
    turn[:2, :2] = [[c, -s], [s, c]]
    box = turn @ np.diag([*BOX_HALF, 1.0])
    box[:3, 3] = BOX_CENTRE
    sphere = np.diag([SPHERE_RADIUS] * 3 + [1.0])
    sphere[:3, 3] = SPHERE_CENTRE
    return Scene(look_down(), [Box("Box", white, box), Sphere("Sphere", white, sphere)], [],
                 ambient=(1.0, 1.0, 1.0))  # fmt: skip


def coverage_reference(per_side=64):
    """Exact coverage per pixel, to within the 1/4096 of a 64 x 64 ray grid."""
    eye = np.array([0.0, 0.0, EYE_HEIGHT])
    covered = np.zeros((SIZE, SIZE))
    c, s = math.cos(TURN), math.sin(TURN)
    to_box = np.array([[c, s, 0.0], [-s, c, 0.0], [0.0, 0.0, 1.0]])  # the turn's inverse
    for row in range(SIZE):
        d = pixel_rays(per_side)[row]  # (SIZE, k, 3)
        # Sphere: |eye + t d - c|^2 = r^2 has a real root
        oc = eye - SPHERE_CENTRE
        b = d @ oc
        hit = b * b - (oc @ oc - SPHERE_RADIUS**2) >= 0.0
        # Box: slabs in the box's frame
        o = to_box @ (eye - BOX_CENTRE)
        db = d @ to_box.T
        with np.errstate(divide="ignore", invalid="ignore"):
            t1, t2 = (-BOX_HALF - o) / db, (BOX_HALF - o) / db
        near = np.nanmax(np.minimum(t1, t2), axis=-1)
        far = np.nanmin(np.maximum(t1, t2), axis=-1)
        hit |= (near <= far) & (far > 0.0)
        covered[row] = hit.mean(axis=-1)
    return covered


AA_SIDES = {"grid": [1, 2, 3, 4, 6, 8, 12, 16], "jittered": [1, 2, 3, 4, 6, 8, 12, 16],
            "random": [1, 2, 3, 4, 6, 8, 12, 16]}  # fmt: skip


def timed_render(scene, settings, runs=2):
    """(linear RGB image, render seconds) of the fastest of `runs` renders."""
    best = None
    for _ in range(runs):
        output = render(scene, settings)
        if best is None or output.stats.render_s < best.stats.render_s:
            best = output
    return best.image[..., :3].astype(float), best.stats.render_s


def chart_antialiasing():
    reference = coverage_reference()
    scene = edge_scene()
    rows = []
    for pattern, sides in AA_SIDES.items():
        for n in sides:
            settings = RenderSettings(
                SIZE, SIZE, pixel_samples=n, pixel_sampling=pattern, shadow_samples=16
            )
            image, seconds = timed_render(scene, settings, runs=5)
            rmse = float(np.sqrt(np.mean((image[..., 0] - reference) ** 2)))
            rows.append((pattern, n * n, seconds, rmse))
    return rows


# --- chart 2: soft shadows ----------------------------------------------------------------
LIGHT_CENTRE = np.array([0.0, 0.0, 4.0])
LIGHT_U, LIGHT_V = np.array([2.0, 0.0, 0.0]), np.array([0.0, 1.5, 0.0])
OCCLUDER_CENTRE, OCCLUDER_HALF = np.array([0.3, -0.2, 1.5]), np.array([0.5, 0.35, 0.25])


def shadow_scene():
    floor = np.diag([20.0, 20.0, 0.5, 1.0])
    floor[2, 3] = -0.5  # top face at z = 0
    occluder = np.diag([*OCCLUDER_HALF, 1.0])
    occluder[:3, 3] = OCCLUDER_CENTRE
    white = Material((1.0, 1.0, 1.0))
    light = AreaLight(tuple(LIGHT_CENTRE), tuple(LIGHT_U), tuple(LIGHT_V), (1.0, 1.0, 1.0),
                      (1.0, 0.0, 0.0))  # fmt: skip
    return Scene(look_down(), [Box("Floor", white, floor), Box("Occluder", white, occluder)],
                 [light])  # fmt: skip


def _gauss_square(order=24):
    x, w = np.polynomial.legendre.leggauss(order)
    return (x + 1.0) / 2.0, w / 2.0


def _triangle_rule(order=12):
    """Points (barycentric a, b) and weights on the unit triangle (area 1/2), from a tensor
    Gauss rule through the Duffy collapse: exact for smooth integrands to high order."""
    x, w = _gauss_square(order)
    s, t = np.meshgrid(x, x, indexing="ij")
    ws = np.outer(w, w)
    return s.ravel(), (s * t).ravel(), (ws * s).ravel()


def _cos_to(points, p):
    """cos of the angle at floor point p (normal +z) towards light points (..., 3)."""
    v = points - p
    return v[..., 2] / np.linalg.norm(v, axis=-1)


def _cross2(a, b):
    """The z of the cross product of two 2-D vectors (numpy 2 refuses 2-D np.cross)."""
    return a[0] * b[1] - a[1] * b[0]


def _convex_hull(points):
    """Counter-clockwise hull of 2-D points (monotone chain)."""
    pts = sorted(map(tuple, points))

    def half(seq):
        out = []
        for q in seq:
            while len(out) >= 2 and _cross2(np.subtract(out[-1], out[-2]),
                                            np.subtract(q, out[-2])) <= 0:  # fmt: skip
                out.pop()
            out.append(q)
        return out

    lower, upper = half(pts), half(reversed(pts))
    return np.array(lower[:-1] + upper[:-1])


def _clip(polygon, x0, x1, y0, y1):
    """Sutherland-Hodgman clip of a convex polygon to an axis-aligned rectangle."""
    for axis, bound, keep_above in ((0, x0, True), (0, x1, False), (1, y0, True), (1, y1, False)):
        out = []
        for i in range(len(polygon)):
            a, b = polygon[i - 1], polygon[i]
            a_in = a[axis] >= bound if keep_above else a[axis] <= bound
            b_in = b[axis] >= bound if keep_above else b[axis] <= bound
            if a_in != b_in:
                f = (bound - a[axis]) / (b[axis] - a[axis])
                out.append(a + f * (b - a))
            if b_in:
                out.append(b)
        polygon = np.array(out)
        if len(polygon) == 0:
            break
    return polygon


def irradiance_reference(p):
    """(1/A) x integral over the light of cos(theta) x visibility, for floor point p."""
    s, w = _gauss_square()
    a, b = np.meshgrid(s - 0.5, s - 0.5, indexing="ij")
    grid = LIGHT_CENTRE + a[..., None] * LIGHT_U + b[..., None] * LIGHT_V
    total = float(np.sum(np.outer(w, w) * _cos_to(grid, p)))  # the light's area is 1 here
    corners = OCCLUDER_CENTRE + OCCLUDER_HALF * np.array(
        [[x, y, z] for x in (-1, 1) for y in (-1, 1) for z in (-1, 1)]
    )
    scale = (LIGHT_CENTRE[2] - p[2]) / (corners[:, 2] - p[2])
    shadow = (p + (corners - p) * scale[:, None])[:, :2]
    half_u, half_v = LIGHT_U[0] / 2.0, LIGHT_V[1] / 2.0
    polygon = _clip(_convex_hull(shadow), -half_u, half_u, -half_v, half_v)
    if len(polygon) < 3:
        return total
    ta, tb, tw = _triangle_rule()
    hidden = 0.0
    for i in range(1, len(polygon) - 1):
        v0, v1, v2 = polygon[0], polygon[i], polygon[i + 1]
        area2 = abs(_cross2(v1 - v0, v2 - v0))
        xy = v0 + np.outer(ta - tb, v1 - v0) + np.outer(tb, v2 - v0)
        q = np.column_stack([xy, np.full(len(xy), LIGHT_CENTRE[2])])
        hidden += area2 * np.sum(tw * _cos_to(q, p))
    return total - hidden / (LIGHT_U[0] * LIGHT_V[1])


def floor_reference(per_side=1):
    """Reference per pixel: the mean over the pixel's per_side^2 grid points (the camera rays
    of the "grid" pattern); NaN where any of them sees the occluder, not the floor."""
    rows, columns = np.divmod(np.arange(SIZE * SIZE), SIZE)
    return floor_reference_at(per_side, rows, columns).reshape(SIZE, SIZE)


def floor_reference_at(per_side, rows, columns):
    """`floor_reference` at the pixels (rows[i], columns[i]) alone."""
    d = pixel_rays(per_side)[rows, columns]
    eye = np.array([0.0, 0.0, EYE_HEIGHT])
    with np.errstate(divide="ignore", invalid="ignore"):
        t1 = (OCCLUDER_CENTRE - OCCLUDER_HALF - eye) / d
        t2 = (OCCLUDER_CENTRE + OCCLUDER_HALF - eye) / d
    blocked = np.nanmax(np.minimum(t1, t2), axis=-1) <= np.nanmin(np.maximum(t1, t2), axis=-1)
    blocked = blocked.any(axis=-1)
    reference = np.full(len(d), np.nan)
    floor_points = eye + d * (EYE_HEIGHT / -d[..., 2])[..., None]
    for i in np.nonzero(~blocked)[0]:
        reference[i] = np.mean([irradiance_reference(p) for p in floor_points[i]])
    return reference


SHADOW_COUNTS = [1, 2, 4, 8, 16, 32, 64, 128, 256]


def chart_shadows():
    """Each pattern at one camera ray per pixel, so a pixel's error is its shadow estimate's;
    and the default pattern at the default n x n camera rays, as a default render has it."""
    rows = []
    scene = shadow_scene()
    lines = [(pattern, 1, pattern) for pattern in ("uniform", "stratified", "halton")]
    side = RenderSettings.pixel_samples
    lines.append((SHADOW_DEFAULT[0], side, f"{SHADOW_DEFAULT[0]}, {side}x{side} camera rays"))
    references = {}
    for pattern, per_side, label in lines:
        if per_side not in references:
            references[per_side] = floor_reference(per_side)
        reference = references[per_side]
        floor = np.isfinite(reference)
        for count in SHADOW_COUNTS:
            settings = RenderSettings(SIZE, SIZE, shadow_samples=count, shadow_sampling=pattern,
                                      pixel_samples=per_side)  # fmt: skip
            image, seconds = timed_render(scene, settings, runs=5)
            rmse = float(np.sqrt(np.mean((image[..., 0][floor] - reference[floor]) ** 2)))
            rows.append((label, count, seconds, rmse))
    return rows


# --- output -------------------------------------------------------------------------------
def write_chart(name, title, rows, default, sample_label, prefix,
                xlabel="render time (s), 64 x 64",
                ylabel="RMSE against the exact answer"):  # fmt: skip
    """Write the chart and its CSV; print {prefix}_default_rmse and _s, and every row."""
    RESULTS.mkdir(exist_ok=True)
    with open(RESULTS / f"{name}.csv", "w", newline="") as f:
        writer = csv.writer(f)
        writer.writerow(["pattern", sample_label, "render_s", "rmse"])
        writer.writerows(rows)
    fig, ax = plt.subplots(figsize=(6.5, 4.5))
    for pattern in dict.fromkeys(r[0] for r in rows):
        mine = [r for r in rows if r[0] == pattern]
        ax.plot([r[2] for r in mine], [r[3] for r in mine], "o-", label=pattern)
        for r in mine:
            ax.annotate(str(r[1]), (r[2], r[3]), fontsize=7, xytext=(3, 3),
                        textcoords="offset points")  # fmt: skip
    chosen = next(r for r in rows if (r[0], r[1]) == default)
    ax.plot(chosen[2], chosen[3], "k*", markersize=16, label=f"default: {default[0]} {default[1]}")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    ax.set_title(title)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend()
    fig.tight_layout()
    fig.savefig(RESULTS / f"{name}.png", dpi=120)
    plt.close(fig)
    print(f"{prefix}_default_rmse: {chosen[3]:.5f}")
    print(f"{prefix}_default_s: {chosen[2]:.4f}")
    for r in rows:
        print(f"  {prefix} {r[0]:>10} {r[1]:>4} {sample_label}  {r[2]:.4f} s  rmse {r[3]:.5f}")


def main():
    render(edge_scene(), RenderSettings(4, 4))  # load the kernels before timing
    aa = chart_antialiasing()
    write_chart("antialiasing", "Anti-aliasing: error against time (labels: rays/pixel)", aa,
                (AA_DEFAULT[0], AA_DEFAULT[1] ** 2), "samples", "aa")  # fmt: skip
    shadows = chart_shadows()
    side = RenderSettings.pixel_samples
    default = (f"{SHADOW_DEFAULT[0]}, {side}x{side} camera rays", SHADOW_DEFAULT[1])
    write_chart("shadows", "Soft shadows: error against time (labels: shadow rays)", shadows,
                default, "shadow_rays", "shadow")  # fmt: skip


if __name__ == "__main__":
    main()
