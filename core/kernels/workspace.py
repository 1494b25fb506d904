"""Per-thread scratch arrays, allocated once per tile rather than once per ray."""

from typing import NamedTuple

import numpy as np

from core.kernels.bvh_build import MAX_TREE_DEPTH


class Workspace(NamedTuple):
    top_stack: np.ndarray  # int32 (MAX_TREE_DEPTH,): top-level nodes waiting
    top_stack_t: np.ndarray  # float64: their entry distances
    stack: np.ndarray  # int32: mesh-level nodes waiting
    stack_t: np.ndarray  # float64
    ray_origin: np.ndarray  # float64 (n, 3): secondary rays waiting to be traced
    ray_direction: np.ndarray  # float64 (n, 3)
    ray_weight: np.ndarray  # float64 (n, 3): what their colour is multiplied by
    ray_depth: np.ndarray  # int64 (n,): bounces so far


def new_workspace(max_depth: int) -> Workspace:
    # Depth-first, each shading point pops one ray and pushes at most two, so no more than
    # max_depth + 2 rays ever wait
    rays = max_depth + 2
    return Workspace(
        np.empty(MAX_TREE_DEPTH, np.int32),
        np.empty(MAX_TREE_DEPTH),
        np.empty(MAX_TREE_DEPTH, np.int32),
        np.empty(MAX_TREE_DEPTH),
        np.empty((rays, 3)),
        np.empty((rays, 3)),
        np.empty((rays, 3)),
        np.empty(rays, np.int64),
    )
