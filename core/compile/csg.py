"""CSG trees into postfix programs over rows of the shape table.

Each operand of a tree becomes a row of its own, after the scene's shapes, with its world
transform composed from its ancestors' (so the kernels never chain transforms); the tree
becomes a program: a step >= 0 names an operand row, a negative step combines the two span
lists on top (see `core.kernels.csg`). A cutter shared by several trees, or used twice in
one, gets a row per use: rows are cheap, and each use may sit under a different transform.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ..checks import valid_affine
from ..errors import SceneError
from ..model import Csg, Shape
from ..vocabulary import CSG_INTERSECTION, CSG_OPERATIONS, CSG_UNION, MAX_OPERANDS


@dataclass
class CsgTables:
    operands: list = field(default_factory=list)  # (shape, world_from_object) per row
    ranges: list = field(default_factory=list)  # (first, end) program steps per tree
    program: list = field(default_factory=list)


def pack_csg(scene_shapes: list) -> tuple[CsgTables, dict[int, int]]:
    """Every CSG tree among the scene's shapes; for each one's row, its tree's index."""
    tables, tree_of_row = CsgTables(), {}
    for row, shape in enumerate(scene_shapes):
        if isinstance(shape, Csg):
            tree_of_row[row] = add_csg(tables, shape, len(scene_shapes))
    return tables, tree_of_row


def add_csg(tables: CsgTables, root: Csg, first_row: int) -> int:
    """Append `root`'s operand rows (numbered from first_row + rows so far) and program;
    returns the tree's index in `tables.ranges`."""
    start = len(tables.program)
    leaves_before = len(tables.operands)
    _emit(tables, root, np.asarray(root.world_from_object, float), first_row)
    if len(tables.operands) - leaves_before > MAX_OPERANDS:
        raise SceneError(
            root.owner,
            "operands",
            f"has {len(tables.operands) - leaves_before} operands; at most {MAX_OPERANDS} "
            "fit one CSG tree",
        )
    tables.ranges.append((start, len(tables.program)))
    return len(tables.ranges) - 1


def _emit(tables: CsgTables, node: Shape, world: np.ndarray, first_row: int) -> None:
    if not valid_affine(world[None])[0]:
        # Each transform passed on its own, but their product is (numerically) singular
        raise SceneError(
            node.owner,
            "world_from_object",
            "composed with the transforms of the CSG nodes above it, is singular or not "
            "finite (scales that cancel to nothing); give the operand and its nodes scales "
            "whose product is not zero",
        )
    if not isinstance(node, Csg):
        tables.program.append(first_row + len(tables.operands))
        tables.operands.append((node, world))
        return
    for operand in (node.left, node.right):
        _emit(tables, operand, world @ np.asarray(operand.world_from_object, float), first_row)
    tables.program.append(CSG_OPERATIONS[node.operation])


def owner_rows(tables: CsgTables, tree_of_row: dict, scene_rows: int) -> list[int]:
    """For every row (the scene's shapes, then the CSG operands), the scene shape it belongs
    to: itself, or the top node of the tree it is an operand of."""
    owners = list(range(scene_rows)) + [-1] * len(tables.operands)
    for row, tree in tree_of_row.items():
        first, end = tables.ranges[tree]
        for step in tables.program[first:end]:
            if step >= 0:
                owners[step] = row
    return owners


def csg_world_box(program: list, first: int, end: int, lo: np.ndarray, hi: np.ndarray):
    """World box of the tree whose steps are program[first:end], from its operand rows'
    boxes lo/hi: a union spans both operands' boxes, an intersection their overlap, a
    difference its left operand's. An empty overlap gives lo > hi."""
    boxes = []
    for step in program[first:end]:
        if step >= 0:
            boxes.append((lo[step], hi[step]))
            continue
        (a_lo, a_hi), (b_lo, b_hi) = boxes[-2], boxes[-1]
        del boxes[-2:]
        if step == CSG_UNION:
            boxes.append((np.minimum(a_lo, b_lo), np.maximum(a_hi, b_hi)))
        elif step == CSG_INTERSECTION:
            boxes.append((np.maximum(a_lo, b_lo), np.minimum(a_hi, b_hi)))
        else:
            boxes.append((a_lo, a_hi))
    return boxes[0]
