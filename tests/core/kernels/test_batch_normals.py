"""The batch kernel `closest_normals` (what chart 4 of the benchmarks measures with), checked
against the numpy ray-shape reference of that chart, and the chart's tessellations."""

import numpy as np
import pytest

from core import Mesh
from core.kernels.workspace import new_workspace
from tests.benchmarks import bench_analytic_vs_mesh as chart
from tests.benchmarks.tessellation import tessellate
from tests.support.probe import packed_shapes, surface

STACKS = new_workspace(0).stacks


def centre_rays(size=48):
    rows, cols = (a.ravel() for a in np.mgrid[0:size, 0:size])
    return chart.pixel_rays(rows * chart.SIZE // size, cols * chart.SIZE // size, 1)[:, 0]


@pytest.mark.parametrize("kind", chart.KINDS)
def test_exact_shapes_agree_with_the_numpy_reference(kind):
    d = centre_rays()
    hit, _, normal = chart.exact_hits(kind, d)
    ours_hit, ours = chart.traced(packed_shapes(chart.analytic(kind)), d, STACKS)
    assert 200 < hit.sum() < len(d) - 200
    np.testing.assert_array_equal(ours_hit, hit)
    np.testing.assert_allclose(ours[hit], normal[hit], atol=1e-9)
    assert not ours[~hit].any()


def test_normals_match_the_single_ray_surface_query():
    mesh = Mesh("Torus mesh", mesh=tessellate("torus", 2_000))
    packed = packed_shapes(mesh)
    d = centre_rays(24)
    hit, normals = chart.traced(packed, d, STACKS)
    for i in np.flatnonzero(hit)[::7]:
        found = surface(packed, chart.EYE, d[i])
        np.testing.assert_allclose(normals[i], found[4], atol=1e-12)


@pytest.mark.parametrize("kind", chart.KINDS)
def test_tessellations_are_closed_outward_and_converge(kind):
    errors = []
    for triangles in (500, 8_000):
        mesh = tessellate(kind, triangles)
        assert abs(len(mesh.triangles) - triangles) < 0.1 * triangles
        assert mesh.open_edge_count() == 0
        corners = mesh.vertices[mesh.triangles]
        face = np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0])
        assert np.all(np.einsum("ij,ij->i", face, mesh.corner_normals.sum(axis=1)) > 0)
        packed = packed_shapes(Mesh(kind, mesh=mesh))
        errors.append(chart.normal_error(kind, packed, STACKS))
    # Smooth normals interpolated between exact corner normals: the error falls as the
    # square of the cell size, 16x for 16x the triangles; ask for 8x
    assert errors[1] < errors[0] / 8.0
