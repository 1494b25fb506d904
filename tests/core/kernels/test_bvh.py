"""The BVH against brute force, meshes (instancing, smooth normals, UVs, degenerate faces),
and the BVH builder's own invariants."""

import numba
import numpy as np
import pytest

from core import Box, Mesh, RenderSettings, Scene, Sphere, Torus, TriangleMesh, render
from core.compile import compile_scene
from core.kernels.bvh_build import build_bvh
from core.kernels.bvh_collapse import collapse_to_wide
from core.kernels.bvh_wide import WIDTH, leaf_range
from core.kernels.shapes import NO_HIT, SHAPE_MESH, intersect_analytic
from core.kernels.triangles import LEAF_WIDTH, intersect_triangle, permuted, shear_setup
from core.kernels.vec import affine_point, affine_vector
from tests.support.meshes import icosphere
from tests.support.probe import hits, surface
from tests.support.reference_shapes import random_affine

RNG = np.random.default_rng(7)


@numba.njit
def brute_force(geo, surf, origins, directions):
    """Every ray against every shape and every triangle, no BVH: (t, shape, part)."""
    n = origins.shape[0]
    out_t, out_shape, out_part = np.full(n, NO_HIT), np.full(n, -1), np.full(n, -1)
    for r in range(n):
        o = (origins[r, 0], origins[r, 1], origins[r, 2])
        d = (directions[r, 0], directions[r, 1], directions[r, 2])
        for s in range(geo.shape_kind.shape[0]):
            oo = affine_point(geo.shape_object_from_world, s, o)
            dd = affine_vector(geo.shape_object_from_world, s, d)
            if geo.shape_kind[s] == SHAPE_MESH:
                mesh = geo.shape_index[s]
                first = surf.mesh_tri_offset[mesh]
                last = geo.tri_corners.shape[0] * LEAF_WIDTH  # slots
                if mesh + 1 < len(geo.mesh_root):
                    last = surf.mesh_tri_offset[mesh + 1]
                shear = shear_setup(dd)
                o_sheared = permuted(oo, shear)
                for tri in range(first, last):
                    t, _, _, _ = intersect_triangle(
                        geo.tri_corners, tri, o_sheared, shear, 0.0, out_t[r]
                    )
                    if t < out_t[r]:
                        out_t[r], out_shape[r], out_part[r] = t, s, tri
            else:
                t, part = intersect_analytic(
                    geo.shape_kind[s], geo.shape_param[s, 0], geo.shape_param[s, 1], oo, dd, 0.0,
                    out_t[r],
                )  # fmt: skip
                if t < out_t[r]:
                    out_t[r], out_shape[r], out_part[r] = t, s, part
    return out_t, out_shape, out_part


def random_scene(rng, shapes=60):
    soup = TriangleMesh(rng.uniform(-1, 1, size=(300, 3)), rng.integers(0, 300, size=(200, 3)))
    ball_vertices, ball_triangles = icosphere(2)
    ball = TriangleMesh(ball_vertices, ball_triangles, smooth=True)
    out = []
    for i in range(shapes):
        m = random_affine(rng, translate=8.0) @ np.diag([0.3, 0.3, 0.3, 1.0])
        choice = i % 5
        if choice == 0:
            out.append(Mesh(f"soup{i}", world_from_object=m, mesh=soup))
        elif choice == 1:
            out.append(Mesh(f"ball{i}", world_from_object=m, mesh=ball))
        elif choice == 2:
            out.append(Torus(f"torus{i}", world_from_object=m, major_radius=1, minor_radius=0.3))
        else:
            out.append((Sphere, Box)[choice - 3](f"s{i}", world_from_object=m))
    return Scene(shapes=out)


@pytest.mark.parametrize("seed", range(3))
def test_bvh_returns_exactly_what_brute_force_returns(seed):
    rng = np.random.default_rng(seed)
    scene = random_scene(rng)
    packed = compile_scene(scene, RenderSettings(8, 8, pixel_samples=1)).packed
    centres = np.array([s.world_from_object[:3, 3] for s in scene.shapes])
    origins = rng.uniform(-12, 12, size=(3000, 3))
    directions = centres[rng.integers(0, len(centres), 3000)] - origins
    directions += rng.normal(size=(3000, 3)) * 0.3
    directions /= np.linalg.norm(directions, axis=1, keepdims=True)
    t, shape, part = hits(packed, origins, directions)
    bt, bshape, bpart = brute_force(packed.geometry, packed.surfaces, origins, directions)
    assert (shape >= 0).sum() > 1000
    np.testing.assert_array_equal(t, bt)
    np.testing.assert_array_equal(shape, bshape)
    np.testing.assert_array_equal(part, bpart)


def test_instances_share_one_copy_of_the_triangles():
    vertices, triangles = icosphere(3)
    ball = TriangleMesh(vertices, triangles)
    many = [Mesh(f"b{i}", world_from_object=np.eye(4) + np.eye(4, k=3) * i, mesh=ball)
            for i in range(50)]  # fmt: skip
    one = compile_scene(Scene(shapes=many[:1]), RenderSettings(8, 8, pixel_samples=1))
    fifty = compile_scene(Scene(shapes=many), RenderSettings(8, 8, pixel_samples=1))
    assert fifty.triangles == one.triangles == len(triangles)
    assert fifty.mesh_bytes == one.mesh_bytes


def test_builder_invariants_on_random_boxes():
    rng = np.random.default_rng(3)
    centre = rng.uniform(-5, 5, size=(5000, 3))
    lo, hi = centre - rng.uniform(0, 0.2, size=(5000, 3)), centre + 0.1
    node_lo, node_hi, info, order = build_bvh(lo, hi, 4, 1.0)
    assert sorted(order) == list(range(5000))
    leaves = info[:, 1] > 0
    assert info[leaves, 1].sum() == 5000 and info[leaves, 1].max() <= 4
    for node in np.flatnonzero(~leaves):
        for child in (info[node, 0], info[node, 0] + 1):
            assert np.all(node_lo[child] >= node_lo[node]) and np.all(
                node_hi[child] <= node_hi[node]
            )
    for node in np.flatnonzero(leaves):
        members = order[info[node, 0] : info[node, 0] + info[node, 1]]
        assert np.all(lo[members] >= node_lo[node]) and np.all(hi[members] <= node_hi[node])


@pytest.mark.parametrize("count", [1, 3, 5, 5000])
def test_wide_tree_keeps_every_triangle_once_inside_its_parents_boxes(count):
    rng = np.random.default_rng(count)
    centre = rng.uniform(-5, 5, size=(count, 3))
    lo, hi = centre - rng.uniform(0, 0.2, size=(count, 3)), centre + 0.1
    node_lo, node_hi, info, order = build_bvh(lo, hi, 4, 1.0)
    boxes, links = collapse_to_wide(node_lo.astype(np.float32), node_hi.astype(np.float32), info)
    seen = np.zeros(count, int)
    reached = np.zeros(len(links), int)
    pending = [(0, np.full(3, -np.inf), np.full(3, np.inf))]
    while pending:
        node, parent_lo, parent_hi = pending.pop()
        reached[node] += 1
        for c in range(WIDTH):
            child_lo, child_hi = boxes[node, :3, c], boxes[node, 3:, c]
            if np.all(child_lo > child_hi):
                assert links[node, c] == -1  # an unused slot
                continue
            assert np.all(child_lo >= parent_lo) and np.all(child_hi <= parent_hi)
            if links[node, c] >= 0:
                pending.append((links[node, c], child_lo, child_hi))
            else:
                first, end = leaf_range(links[node, c])
                assert 1 <= end - first <= 4
                seen[first:end] += 1
                members = order[first:end]
                assert np.all(child_lo <= lo[members].min(axis=0) + 1e-6)
                assert np.all(child_hi >= hi[members].max(axis=0) - 1e-6)
    assert np.all(seen == 1) and np.all(reached == 1)


def least_collapse_area(lo, hi, info):
    """By exhaustion: the least summed half area of the wide nodes of any collapse of the
    binary tree, over every choice of which inner nodes below the root are wide nodes."""
    inner = [m for m in range(1, len(info)) if info[m, 1] == 0]
    extent = hi.astype(np.float64) - lo.astype(np.float64)
    area = (extent * np.roll(extent, 1, axis=1)).sum(axis=1)

    def child_count(m, wide):
        """Wide children of wide node m: the nearest descendants that are leaves or wide."""
        count, pending = 0, [info[m, 0], info[m, 0] + 1]
        while pending:
            x = pending.pop()
            if info[x, 1] > 0 or x in wide:
                count += 1
            else:
                pending += [info[x, 0], info[x, 0] + 1]
        return count

    best = np.inf
    for mask in range(1 << len(inner)):
        wide = {0} | {m for b, m in enumerate(inner) if mask >> b & 1}
        if all(child_count(m, wide) <= WIDTH for m in wide):
            best = min(best, sum(area[m] for m in wide))
    return best


@pytest.mark.parametrize("seed", range(6))
def test_wide_tree_has_the_least_node_area_of_any_collapse(seed):
    """The collapse minimises the summed surface area of its wide nodes (what a ray's node
    visits cost; every leaf is tested alike in any collapse): checked against every
    collapse of small random trees with 13 to 16 leaves."""
    rng = np.random.default_rng(seed)
    count = 13 + seed % 4
    centre = rng.uniform(-5, 5, size=(count, 3)) * rng.uniform(0.1, 1.0, size=3)
    lo, hi = centre - rng.uniform(0, 0.5, size=(count, 3)), centre + 0.1
    node_lo, node_hi, info, _ = build_bvh(lo, hi, 1, 1.0)
    lo32, hi32 = node_lo.astype(np.float32), node_hi.astype(np.float32)
    boxes, links = collapse_to_wide(lo32, hi32, info)
    # The collapse's own area: the root's box and every inner child's slot box
    extent = (boxes[:, 3:, :].astype(np.float64) - boxes[:, :3, :]).transpose(0, 2, 1)
    slot_area = (extent * np.roll(extent, 1, axis=2)).sum(axis=2)
    root_extent = hi32[0].astype(np.float64) - lo32[0]
    achieved = (root_extent * np.roll(root_extent, 1)).sum() + slot_area[links >= 0].sum()
    assert achieved == pytest.approx(least_collapse_area(lo32, hi32, info), rel=1e-12)


def test_identical_boxes_still_give_bounded_leaves():
    lo = np.zeros((1000, 3))
    _, _, info, order = build_bvh(lo, lo + 1.0, 4, 1.0)
    assert sorted(order) == list(range(1000)) and info[info[:, 1] > 0, 1].max() <= 4


def flat_square(smooth, **extra):
    """Two triangles of the square [-1, 1]^2 at z = 0, facing +z."""
    v = np.array([[-1, -1, 0], [1, -1, 0], [1, 1, 0], [-1, 1, 0]], float)
    return TriangleMesh(v, np.array([[0, 1, 2], [0, 2, 3]]), smooth=smooth, **extra)


def test_smooth_faces_interpolate_normals_and_flat_faces_do_not():
    tilted = np.array([[-1, -1, 1], [1, -1, 1], [1, 1, 1], [-1, 1, 1]], float)
    for smooth in (True, False):
        mesh = flat_square(np.array([smooth, smooth]), vertex_normals=tilted)
        packed = compile_scene(Scene(shapes=[Mesh(mesh=mesh)]), RenderSettings(8, 8)).packed
        found = surface(packed, (0.5, -0.25, 3.0), (0.0, 0.0, -1.0))
        _, t, point, geometric, shading, _ = found
        assert t == pytest.approx(3.0)
        np.testing.assert_allclose(geometric, (0, 0, 1), atol=1e-15)
        if smooth:
            # Barycentric blend of the corner normals at (0.5, -0.25)
            b = {0: 0.25, 1: 0.375, 2: 0.375}
            n = sum(w * tilted[k] for k, w in b.items())
            np.testing.assert_allclose(shading, n / np.linalg.norm(n), atol=1e-7)
        else:
            np.testing.assert_allclose(shading, (0, 0, 1), atol=1e-15)


def test_corner_uvs_interpolate_and_vertex_normals_come_from_faces():
    uvs = np.array([[[0, 0], [1, 0], [1, 1]], [[0, 0], [1, 1], [0, 1]]], float)
    mesh = flat_square(True, corner_uvs=uvs)
    packed = compile_scene(
        Scene(shapes=[Mesh(mesh=mesh)]), RenderSettings(8, 8, pixel_samples=1)
    ).packed
    _, _, _, _, shading, (u, v) = surface(packed, (0.5, -0.25, 3.0), (0.0, 0.0, -1.0))
    assert (u, v) == (pytest.approx(0.75), pytest.approx(0.375))
    np.testing.assert_allclose(shading, (0, 0, 1), atol=1e-7)  # a flat mesh: all normals +z


def test_smooth_mesh_without_normals_gets_area_weighted_vertex_normals():
    """At a vertex, the shading normal is the area-weighted mean of the faces around it (the
    report's way); on an icosphere that is close to the radial direction."""
    vertices, triangles = icosphere(2)
    mesh = TriangleMesh(vertices, triangles, smooth=True)
    packed = compile_scene(
        Scene(shapes=[Mesh(mesh=mesh)]), RenderSettings(8, 8, pixel_samples=1)
    ).packed
    v32 = vertices.astype(np.float32).astype(np.float64)
    for k in (0, 5, 40):
        faces = np.flatnonzero((triangles == k).any(axis=1))
        a, b, c = (v32[triangles[faces, i]] for i in range(3))
        expected = np.cross(b - a, c - a).sum(axis=0)
        expected /= np.linalg.norm(expected)
        # Aim at the vertex itself from outside along its direction
        _, _, _, _, shading, _ = surface(packed, v32[k] * 3.0, -v32[k] / np.linalg.norm(v32[k]))
        np.testing.assert_allclose(shading, expected, atol=1e-6)


def test_degenerate_triangles_are_dropped_with_a_count():
    v = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [2, 0, 0]], float)
    mesh = TriangleMesh(v, np.array([[0, 1, 2], [0, 1, 3], [2, 2, 1]]), name="Sliver")
    compiled = compile_scene(
        Scene(shapes=[Mesh("Sliver", mesh=mesh)]), RenderSettings(8, 8, pixel_samples=1)
    )
    assert compiled.triangles == 1
    assert compiled.warnings == ["mesh 'Sliver': dropped 2 degenerate (zero-area) triangles"]
    out = render(Scene(shapes=[Mesh("Sliver", mesh=mesh)]), RenderSettings(4, 4, pixel_samples=1))
    assert out.warnings == compiled.warnings


def test_a_mesh_with_no_triangles_left_renders_background():
    v = np.zeros((3, 3))
    scene = Scene(shapes=[Mesh("Flat", mesh=TriangleMesh(v, np.array([[0, 1, 2]])))],
                  background=(0.25, 0.5, 0.75))  # fmt: skip
    image = render(scene, RenderSettings(4, 4, pixel_samples=1)).image
    np.testing.assert_array_equal(image[..., :3], np.broadcast_to((0.25, 0.5, 0.75), (4, 4, 3)))


def test_watertight_a_million_rays_at_shared_edges_and_vertices():
    """Rays through points exactly on the shared edges and at the vertices of a closed convex
    mesh, from outside towards a point inside and from a point inside outwards, must all hit
    it at that point: none slips through a crack between triangles."""
    rng = np.random.default_rng(11)
    vertices, triangles = icosphere(4)
    matrix = random_affine(rng, translate=3.0)
    packed = compile_scene(
        Scene(shapes=[Mesh(world_from_object=matrix, mesh=TriangleMesh(vertices, triangles))]),
        RenderSettings(8, 8, pixel_samples=1),
    ).packed
    v32 = vertices.astype(np.float32).astype(np.float64)
    world = v32 @ matrix[:3, :3].T + matrix[:3, 3]
    edges = np.unique(
        np.sort(np.concatenate([triangles[:, [0, 1]], triangles[:, [1, 2]]]), 1), axis=0
    )
    n = 1_000_000
    pick = rng.integers(0, len(edges), size=n)
    s = rng.uniform(0, 1, size=(n, 1))
    s[: n // 4] = 0.0  # a quarter aimed exactly at vertices
    targets = world[edges[pick, 0]] * (1 - s) + world[edges[pick, 1]] * s
    inner = matrix[:3, 3] + (matrix[:3, :3] @ rng.uniform(-0.4, 0.4, size=(n, 3)).T).T
    away = targets - inner
    away /= np.linalg.norm(away, axis=1, keepdims=True)
    origins = np.where(np.arange(n)[:, None] % 2 == 0, targets + 10.0 * away, inner)
    directions = np.where(np.arange(n)[:, None] % 2 == 0, -away, away)
    t, shape, _ = hits(packed, origins, directions)
    assert np.all(shape == 0), f"{np.sum(shape != 0)} of {n} rays passed through"
    expected = np.linalg.norm(targets - origins, axis=1)
    np.testing.assert_allclose(t, expected, rtol=1e-6)


@pytest.mark.parametrize("subdivisions", [1, 2, 3, 4])
def test_watertight_rays_through_every_vertex_untransformed(subdivisions):
    """Radial rays at every vertex of an untransformed icosphere: the vertex lies on the
    boxes of the BVH, where culling must not undo the triangle test's decision."""
    vertices, triangles = icosphere(subdivisions)
    mesh = TriangleMesh(vertices, triangles)
    packed = compile_scene(
        Scene(shapes=[Mesh(mesh=mesh)]), RenderSettings(8, 8, pixel_samples=1)
    ).packed
    v32 = vertices.astype(np.float32).astype(np.float64)
    inward = -v32 / np.linalg.norm(v32, axis=1, keepdims=True)
    _, shape, _ = hits(packed, v32 * 3.0, inward)
    _, shape_out, _ = hits(packed, v32 * 0.0, -inward)
    assert np.all(shape == 0) and np.all(shape_out == 0), (np.sum(shape), np.sum(shape_out))
