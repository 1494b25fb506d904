"""The compile step (core.compile) against what the scene says, computed here on its own:
the rows of the shape table, the CSG programs as postfix expressions over those rows, the
inverse transforms, what is shared packed once, and every array in the one layout the
kernels are compiled for."""

import numpy as np

from core import (
    AreaLight,
    Box,
    Csg,
    Cylinder,
    Material,
    Mesh,
    PointLight,
    RenderSettings,
    Scene,
    Sphere,
    Torus,
    TriangleMesh,
)
from core.compile import compile_scene
from core.vocabulary import (
    CSG_OPERATIONS,
    SHAPE_BOX,
    SHAPE_CSG,
    SHAPE_CYLINDER,
    SHAPE_MESH,
    SHAPE_SPHERE,
    SHAPE_TORUS,
)
from tests.support.meshes import icosphere

RNG = np.random.default_rng(20261202)
SETTINGS = RenderSettings(8, 8, pixel_samples=1)
SHARED = Material(diffuse=(0.2, 0.4, 0.6), name="shared")


def placed(x):
    """A random rotation and scale, moved to x along the x axis."""
    q, _ = np.linalg.qr(RNG.normal(size=(3, 3)))
    m = np.eye(4)
    m[:3, :3] = q @ np.diag(RNG.uniform(0.5, 2.0, size=3))
    m[:3, 3] = (x, 0.0, 0.0)
    return m


def the_scene():
    mesh = TriangleMesh(*icosphere(1))
    cutter = Cylinder("Cutter", SHARED, placed(0.0))
    shapes = [
        Sphere("S", SHARED, placed(-6.0)),
        Csg(
            "Cut",
            operation="difference",
            world_from_object=placed(0.0),
            left=Box("Block", Material(name="block")),
            right=Csg("Both", operation="intersection", left=cutter, right=Sphere("Round", SHARED)),
        ),  # fmt: skip
        Mesh("M1", SHARED, placed(3.0), mesh=mesh),
        Mesh("M2", Material(name="other"), placed(6.0), mesh=mesh),
        Torus("T", SHARED, placed(9.0), major_radius=1.0, minor_radius=0.3),
    ]
    lights = [
        PointLight((0.0, 0.0, 9.0), (1.0, 1.0, 1.0)),
        AreaLight((0.0, 0.0, 8.0), (2.0, 0.0, 0.0), (0.0, 3.0, 0.0), (5.0, 5.0, 5.0)),
    ]
    return Scene(shapes=shapes, lights=lights), mesh


def test_shape_rows_are_the_scene_s_shapes_then_the_csg_operands():
    scene, _ = the_scene()
    geo = compile_scene(scene, SETTINGS).packed.geometry
    # The scene's five, then the three leaves of the CSG tree (Block, Cutter, Round)
    expected = [SHAPE_SPHERE, SHAPE_CSG, SHAPE_MESH, SHAPE_MESH, SHAPE_TORUS,
                SHAPE_BOX, SHAPE_CYLINDER, SHAPE_SPHERE]  # fmt: skip
    assert list(geo.shape_kind) == expected
    # The top-level BVH holds the scene's shapes only, each once; operands are reached
    # through their tree
    assert sorted(geo.top_order) == list(range(len(scene.shapes)))


def _evaluate(program, operand_names):
    """The postfix program as a string expression, by a stack, as the kernel reads it."""
    words = {code: name for name, code in CSG_OPERATIONS.items()}
    stack = []
    for step in program:
        if step >= 0:
            stack.append(operand_names[step])
        else:
            right, left = stack.pop(), stack.pop()
            stack.append(f"({left} {words[step]} {right})")
    assert len(stack) == 1, f"program {list(program)} leaves {len(stack)} values"
    return stack[0]


def test_a_csg_tree_packs_into_a_postfix_program_over_its_operand_rows():
    scene, _ = the_scene()
    geo = compile_scene(scene, SETTINGS).packed.geometry
    names = {5: "Block", 6: "Cutter", 7: "Round"}
    first, end = geo.csg_range[geo.shape_index[1]]
    assert _evaluate(geo.csg_program[first:end], names) == (
        "(Block difference (Cutter intersection Round))"
    )


def test_inverse_transforms_are_the_inverses_of_the_world_transforms():
    scene, _ = the_scene()
    geo = compile_scene(scene, SETTINGS).packed.geometry
    for row, shape in enumerate(scene.shapes):
        inverse = np.linalg.inv(shape.world_from_object)[:3]
        np.testing.assert_allclose(geo.shape_object_from_world[row], inverse, atol=1e-12)
    # An operand's world transform is its tree's times its own
    cut = scene.shapes[1]
    cutter_world = cut.world_from_object @ cut.right.left.world_from_object
    np.testing.assert_allclose(
        geo.shape_object_from_world[6], np.linalg.inv(cutter_world)[:3], atol=1e-12
    )


def test_what_shapes_share_is_packed_once():
    scene, mesh = the_scene()
    compiled = compile_scene(scene, SETTINGS)
    packed = compiled.packed
    # Materials by identity: shared, the CSG row's own (unused, as every row has one), block,
    # other
    assert len(packed.materials.diffuse) == 4
    rows = packed.surfaces.shape_material
    assert rows[0] == rows[2] == rows[4] == rows[6] == rows[7]  # every use of SHARED
    np.testing.assert_array_equal(packed.materials.diffuse[rows[0]], SHARED.diffuse)
    # One mesh under two objects: its triangles once, both rows naming the same BVH
    assert compiled.triangles == len(mesh.triangles)
    assert packed.geometry.shape_index[2] == packed.geometry.shape_index[3]


def test_lights_keep_their_values():
    scene, _ = the_scene()
    lights = compile_scene(scene, SETTINGS).packed.lights
    np.testing.assert_array_equal(lights.point_position, [(0.0, 0.0, 9.0)])
    np.testing.assert_array_equal(lights.area_edge_u, [(2.0, 0.0, 0.0)])
    np.testing.assert_array_equal(lights.area_edge_v, [(0.0, 3.0, 0.0)])
    assert lights.sun_toward.shape == (0, 3)


def test_every_array_is_c_contiguous_aligned_and_writable_even_from_strided_input():
    scene, _ = the_scene()
    # A transform that is a Fortran-ordered view: the packed copy must not inherit it
    scene.shapes[0].world_from_object = np.asfortranarray(scene.shapes[0].world_from_object)
    packed = compile_scene(scene, SETTINGS).packed
    for group in packed:
        for name, array in group._asdict().items():
            flags = array.flags
            assert flags.c_contiguous and flags.aligned and flags.writeable, name
