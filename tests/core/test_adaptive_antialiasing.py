"""Adaptive anti-aliasing (RenderSettings.adaptive_threshold, core.kernels.adaptive_tile):
one ray at each pixel corner and one at each pixel's centre, a pixel's n x n rays only
where they disagree.

Against the truth: a flat white disk on black seen straight on, whose pixels are the
share of each pixel the disk covers (computed here by a 256 x 256 quadrature per pixel).
Pixels wholly inside or outside the disk are exact from their corners and centre; pixels on its
edge are the fixed grid's, bit for bit; the whole picture is no further from the truth
than the fixed grid's, for a fraction of the camera rays. Any tiling and border give the
same pixels, and the passes and Cryptomatte follow the same rays.
"""

import numpy as np

from core import Camera, Material, RenderSettings, Scene, Sphere, render

SIZE, VIEW, RADIUS = 40, 4.0, 1.3  # pixels across, scene units across, the disk's radius
FLAT = Material(diffuse=(1.0, 1.0, 1.0), specular=(0.0, 0.0, 0.0), name="flat")


def disk_scene():
    """A sphere lit by the ambient term alone (colour 1 wherever it is seen, black behind),
    off-centre so that its edge crosses pixels at every angle."""
    world = np.diag([RADIUS, RADIUS, RADIUS, 1.0])
    world[:3, 3] = (0.13, -0.07, 0.0)
    camera = Camera(eye=(0.0, 0.0, 10.0), view=(0.0, 0.0, -1.0), up=(0.0, 1.0, 0.0),
                    projection="orthographic", ortho_height=VIEW)  # fmt: skip
    return Scene(camera, [Sphere("Disk", FLAT, world)], [], ambient=(1.0, 1.0, 1.0))


def coverage() -> np.ndarray:
    """The share of each pixel the disk covers, by quadrature (256 x 256 points a pixel)."""
    k = 256
    edges = (np.arange(SIZE * k) + 0.5) / (SIZE * k) * VIEW - VIEW / 2
    inside_x = (edges - 0.13) ** 2
    inside_y = (-edges + 0.07) ** 2  # image rows go down, y up
    covered = inside_y[:, None] + inside_x[None, :] < RADIUS**2
    return covered.reshape(SIZE, k, SIZE, k).mean(axis=(1, 3))


def rendered(threshold, **overrides):
    settings = RenderSettings(SIZE, SIZE, pixel_samples=3, adaptive_threshold=threshold,
                              **overrides)  # fmt: skip
    return render(disk_scene(), settings)


def test_flat_pixels_are_exact_and_edge_pixels_are_the_grids_for_a_third_of_the_rays():
    truth = coverage()
    fixed, adaptive = rendered(0.0), rendered(0.02, tile_size=SIZE)
    grid, fast = fixed.image[..., 0].astype(float), adaptive.image[..., 0].astype(float)
    inside, outside = truth == 1.0, truth == 0.0
    assert inside.sum() > 200 and outside.sum() > 200
    edge = ~(inside | outside)
    # Corners and centre of a pixel wholly in or out of the disk agree: the pixel is exact
    assert (fast[inside] == 1.0).all() and (fast[outside] == 0.0).all()
    np.testing.assert_array_equal(adaptive.image[..., 3][inside], 1.0)
    # A pixel the edge crosses has corners on both sides (the disk is wide): its 3 x 3 rays
    np.testing.assert_array_equal(fast[edge], grid[edge])
    # So no further from the truth than the grid, and far fewer camera rays: two a pixel
    # (its corners, shared, and its centre) and nine more on the edge
    fast_error = np.sqrt(np.mean((fast - truth) ** 2))
    grid_error = np.sqrt(np.mean((grid - truth) ** 2))
    assert fast_error <= grid_error, (fast_error, grid_error)
    expected_rays = (SIZE + 1) ** 2 + SIZE**2 + 9 * edge.sum()
    assert abs(adaptive.stats.rays_traced - expected_rays) <= 9 * 8  # a tangent edge or two
    assert adaptive.stats.rays_traced < 0.45 * fixed.stats.rays_traced


def test_a_threshold_of_one_never_refines_and_differences_below_it_do_not_either():
    # Samples differ by at most x / (1 + x) = 1/2 in colour and 1 in alpha: a threshold of 1
    # refines nothing, so every pixel weighs its four corners and its centre
    coarse = rendered(1.0, tile_size=SIZE)  # one tile: every corner traced once
    assert coarse.stats.rays_traced == (SIZE + 1) ** 2 + SIZE**2
    values = coarse.image[..., 0].astype(float)
    # an eighth each corner and half the centre, each 0 or 1 here: a multiple of 1/8
    np.testing.assert_array_equal(values * 8.0, np.round(values * 8.0))
    # and the centre counts for half: on the edge some pixel is no multiple of 1/4, which
    # four corners alone would give
    assert (values * 4.0 != np.round(values * 4.0)).any()


def test_any_tiling_and_border_gives_the_same_pixels():
    whole = rendered(0.02, tile_size=64).image
    tiled = rendered(0.02, tile_size=7, threads=2).image
    np.testing.assert_array_equal(tiled, whole)
    border = rendered(0.02, region=(5, 9, 17, 13)).image
    np.testing.assert_array_equal(border[9:22, 5:22], whole[9:22, 5:22])


def test_the_passes_follow_the_same_rays():
    fixed = rendered(0.0, passes=("depth", "crypto_object"))
    adaptive = rendered(0.02, passes=("depth", "crypto_object"))
    truth = coverage()
    edge = (truth > 0.0) & (truth < 1.0)
    # Refined pixels: the grid's passes exactly; the others: their corners', which for a
    # flat pixel say the same as the grid (the disk's nearest depth, all of one object)
    for name in ("depth", "crypto_object"):
        np.testing.assert_array_equal(adaptive.passes[name][edge], fixed.passes[name][edge])
    coverage_sum = adaptive.passes["crypto_object"][..., 1::2].sum(axis=-1)
    inside = truth == 1.0
    assert (coverage_sum[inside] == 1.0).all() and (coverage_sum[truth == 0.0] == 0.0).all()
    np.testing.assert_array_equal(adaptive.passes["crypto_object"][inside],
                                  fixed.passes["crypto_object"][inside])  # fmt: skip
