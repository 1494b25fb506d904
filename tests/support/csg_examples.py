"""The project report's three CSG examples, shared by the silhouette test and the benchmark."""

import numpy as np

from core import Box, Csg, Cylinder, Sphere


def scaled(sx, sy, sz, rotate_to=None):
    m = np.diag([sx, sy, sz, 1.0])
    if rotate_to == "x":
        m[:3, :3] = np.array([[0, 0, 1.0], [0, 1.0, 0], [-1.0, 0, 0]]) @ m[:3, :3]
    elif rotate_to == "y":
        m[:3, :3] = np.array([[1.0, 0, 0], [0, 0, -1.0], [0, 1.0, 0]]) @ m[:3, :3]
    return m


# The report's examples: (name, first operand, [(operation, operand), ...]); an operand is
# (kind, 4x4 world_from_object)
EXAMPLES = [
    (
        "sphere_and_cube",
        ("sphere", scaled(1, 1, 1)),
        [("intersection", ("cube", scaled(0.78, 0.78, 0.78)))],
    ),
    (
        "three_cylinders",
        ("cylinder", scaled(0.5, 0.5, 1.5)),
        [
            ("union", ("cylinder", scaled(0.5, 0.5, 1.5, "x"))),
            ("union", ("cylinder", scaled(0.5, 0.5, 1.5, "y"))),
        ],
    ),
    (
        "cube_minus_cylinder",
        ("cube", scaled(1, 1, 1)),
        [("difference", ("cylinder", scaled(0.55, 0.55, 1.5, "y")))],
    ),
]  # fmt: skip

ANALYTIC = {"sphere": Sphere, "cube": Box, "cylinder": Cylinder}


def analytic_tree(first, steps):
    kind, matrix = first
    node = ANALYTIC[kind](kind, world_from_object=matrix)
    for operation, (kind, matrix) in steps:
        node = Csg("csg", operation=operation, left=node,
                   right=ANALYTIC[kind](kind, world_from_object=matrix))  # fmt: skip
    return node
