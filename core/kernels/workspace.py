"""Per-thread scratch arrays, allocated once per tile rather than once per ray."""

from typing import NamedTuple

import numpy as np

from ..vocabulary import MAX_OPERANDS
from .bvh_build import MAX_TREE_DEPTH
from .bvh_wide import WIDTH
from .csg import CROSSING_CAPACITY, SPAN_CAPACITY
from .light_pyramid import MAX_CANDIDATES, PYRAMID_ROWS
from .light_samples import STRATA_SLOTS
from .pass_record import ACC_COUNT, REC_COUNT, TERM_ROWS
from .shader_program import LOBE_COUNT, SHADER_STACK
from .shadow_log import PROBES, SHADOW_LOG_SIZE, SHADOW_STATE_SLOTS, VARYING_CAPACITY

# Surfaces one ray may pass straight through (transparent shares, shapes its kind does not
# see): Cycles' Max Bounces > Transparent is 8 by default; leaves on cards need more
MAX_CROSSINGS = 64

# A wide node leaves at most WIDTH - 1 children waiting besides the one visited next,
# and the wide tree is no deeper than the binary one
MESH_STACK_SIZE = (WIDTH - 1) * MAX_TREE_DEPTH + 1


# Slots of Stacks.ray_counts: rays traced to their closest hit; shadow rays answered; shadow
# rays answered without a test because the light's pyramid held no shape
RAYS_TRACED, SHADOW_RAYS, SHADOW_RAYS_UNOBSTRUCTED = 0, 1, 2
RAY_COUNT_SLOTS = 3
# Slots of a corner in Workspace.corners (core.kernels.adaptive_tile): RGB, alpha, then the
# camera ray's record for the passes
CORNER_ALPHA = 3
CORNER_RECORD = 4
CORNER_SLOTS = CORNER_RECORD + REC_COUNT
# Slots of Stacks.occluder: the shape that stopped the thread's last listed shadow ray, and
# its position in the current candidate list (-1 when it is not on it)
OCCLUDER_SHAPE, OCCLUDER_POSITION = 0, 1


class CsgScratch(NamedTuple):
    """Span lists of one ray's CSG evaluation (see core.kernels.csg)."""

    span_f: np.ndarray  # float64 (SPAN_CAPACITY, 2, 3): (t, b1, b2) of entry and exit
    span_i: np.ndarray  # int32 (SPAN_CAPACITY, 2, 2): (shape row, part) of entry and exit
    segments: np.ndarray  # int64 (MAX_OPERANDS,): where each pending operand's list starts
    cross_f: np.ndarray  # float64 (CROSSING_CAPACITY, 3): a mesh operand's crossings
    cross_i: np.ndarray  # int32 (CROSSING_CAPACITY, 2): (triangle, +1 entering / -1 leaving)
    stack: np.ndarray  # int32 (MESH_STACK_SIZE,): the mesh traversal's
    overflow: np.ndarray  # int64 (1,): rays whose spans or crossings did not all fit


class Stacks(NamedTuple):
    """BVH traversal stacks, one for the top level and one for the mesh level, the CSG
    scratch lists, an area light's pyramid and the shapes in it, and the count of rays."""

    top: np.ndarray  # int32 (MAX_TREE_DEPTH,): top-level nodes waiting
    top_t: np.ndarray  # float64: their entry distances
    mesh: np.ndarray  # int32 (MESH_STACK_SIZE,): mesh-level nodes or leaves waiting
    mesh_t: np.ndarray  # float32: their entry distances (the mesh slab test's precision)
    csg: CsgScratch
    ray_counts: np.ndarray  # int64 (RAY_COUNT_SLOTS,)
    pyramid: np.ndarray  # float64 (PYRAMID_ROWS, 4): see core.kernels.light_pyramid
    candidates: np.ndarray  # int32 (MAX_CANDIDATES,): shapes that may meet the pyramid
    occluder: np.ndarray  # int64 (2,): OCCLUDER_SHAPE, OCCLUDER_POSITION
    # one light's points as seen from a shading point (see core.kernels.shading)
    # float64 (shadow samples + PROBES, 5): unit direction xyz, distance, and for lights in
    # Blender's units the sample's weight (core.kernels.emitters)
    light_targets: np.ndarray
    visibility: np.ndarray  # float64 (shadow samples + PROBES,): what reaches the point from each
    # float64 (shadow samples + PROBES, 3): its colour, as a factor of `visibility` per
    # channel (1 unless a coloured transparent surface is crossed; core.kernels.trace)
    visibility_tint: np.ndarray
    # a shading point's lighting split into the passes' terms (core.kernels.pass_record)
    terms: np.ndarray  # float64 (TERM_ROWS, 3)
    # a shading point's shadow rays through surfaces whose share varies (core.kernels.shadow_log)
    shadow_state: np.ndarray  # int64 (SHADOW_STATE_SLOTS,)
    shadow_log: np.ndarray  # float64 (SHADOW_LOG_SIZE,): each ray's visibility
    shadow_log_tint: np.ndarray  # float64 (SHADOW_LOG_SIZE, 3): and its tint
    shadow_tint: np.ndarray  # float64 (3,): the tint of the last `trace.transmittance`
    varying_f: np.ndarray  # float64 (VARYING_CAPACITY, 9): t, b1, b2, the ray's o and d
    varying_i: np.ndarray  # int64 (VARYING_CAPACITY, 3): shape row, part, the ray's number
    # uint64 (STRATA_SLOTS,): the camera sample's place among its pixel's, over which the
    # stratified lights' cells are shared out (core.kernels.light_samples.square_point)
    light_strata: np.ndarray


class RayStack(NamedTuple):
    """Secondary rays waiting to be traced."""

    origin: np.ndarray  # float64 (n, 3)
    direction: np.ndarray  # float64 (n, 3)
    weight: np.ndarray  # float64 (n, 3): what their colour is multiplied by
    depth: np.ndarray  # int64 (n,): bounces so far
    # int64 (n,): the record slot of the term its colour adds to, when passes are made
    branch: np.ndarray
    # int64 (n,): how the ray left its last surface, core.kernels.integrator's RAY_*:
    # reflected, refracted, or reflected off a rough surface (which of a light's Ray
    # Visibility switches, Glossy or Transmission, lets it see the light, or none)
    refracted: np.ndarray
    crossed: np.ndarray  # int64 (n,): surfaces passed straight through so far
    # int64 (n,): the material row of the medium it travels in, -1 air
    # (core.kernels.absorption)
    medium: np.ndarray
    refractions: np.ndarray  # int64 (n,): of its bounces, those that refracted (Light Path)


class Workspace(NamedTuple):
    stacks: Stacks
    rays: RayStack
    # int64 (1,), shared by every tile of a render: non-zero once the render is cancelled,
    # which the tile kernel reads at every pixel and stops
    cancel: np.ndarray
    # the passes (core.kernels.pass_record): a camera ray's record, a pixel's sums, and
    # per camera ray of the pixel, (met something, object id, material id) for Cryptomatte
    record: np.ndarray  # float64 (REC_COUNT,)
    accum: np.ndarray  # float64 (ACC_COUNT,)
    crypto_ids: np.ndarray  # float64 (camera rays per pixel, 3), or (1, 3) without Cryptomatte
    crypto_distinct: np.ndarray  # float64 (the same rows, 2): scratch, (id, rays) per id
    # a shader program's stack and the lobes it adds up (core.kernels.shader_program)
    shader_stack: np.ndarray  # float64 (SHADER_STACK,)
    lobes: np.ndarray  # float64 (LOBE_COUNT,)
    # adaptive anti-aliasing's corners of two rows of pixel edges, (2, tile width + 1,
    # CORNER_SLOTS) (core.kernels.adaptive_tile), or (2, 1, CORNER_SLOTS) without it
    corners: np.ndarray


def new_workspace(
    max_depth: int, shadow_samples: int = 1, cancel=None, crypto_rays: int = 1,
    glossy_samples: int = 0, corner_columns: int = 1,
) -> Workspace:  # fmt: skip
    """Scratch for one tile; `crypto_rays`: the camera rays per pixel when Cryptomatte is
    made (each keeps its ids until the pixel is done), else 1; `glossy_samples` as
    RenderSettings'; `corner_columns`: the tile's width + 1 with adaptive anti-aliasing."""
    # Depth-first, each shading point pops one ray and pushes at most two that bounce, so no
    # more than max_depth + 2 of those ever wait; each surface passed straight through
    # (MAX_CROSSINGS) may leave two more waiting, and a camera ray's rough hit two per
    # glossy sample (a reflected and a refracted ray); a clear coat's reflection one more
    # per sample (at least one)
    rays = max_depth + 3 + 2 * MAX_CROSSINGS + 3 * glossy_samples
    return Workspace(
        Stacks(
            np.empty(MAX_TREE_DEPTH, np.int32),
            np.empty(MAX_TREE_DEPTH),
            np.empty(MESH_STACK_SIZE, np.int32),
            np.empty(MESH_STACK_SIZE, np.float32),
            CsgScratch(
                np.empty((SPAN_CAPACITY, 2, 3)),
                np.empty((SPAN_CAPACITY, 2, 2), np.int32),
                np.empty(MAX_OPERANDS, np.int64),
                np.empty((CROSSING_CAPACITY, 3)),
                np.empty((CROSSING_CAPACITY, 2), np.int32),
                np.empty(MESH_STACK_SIZE, np.int32),
                np.zeros(1, np.int64),
            ),
            np.zeros(RAY_COUNT_SLOTS, np.int64),
            np.zeros((PYRAMID_ROWS, 4)),
            np.zeros(MAX_CANDIDATES, np.int32),
            np.full(2, -1, np.int64),
            # the samples' rows, then adaptive soft shadows' probes (core.kernels.shadow_rays)
            # (direction, distance, weight, an emissive surface's tint: core.kernels.emitters)
            np.zeros((max(shadow_samples, 1) + PROBES, 8)),
            np.zeros(max(shadow_samples, 1) + PROBES),
            np.ones((max(shadow_samples, 1) + PROBES, 3)),
            np.zeros((TERM_ROWS, 3)),
            np.zeros(SHADOW_STATE_SLOTS, np.int64),
            np.zeros(SHADOW_LOG_SIZE),
            np.ones((SHADOW_LOG_SIZE, 3)),
            np.ones(3),
            np.zeros((VARYING_CAPACITY, 9)),
            np.zeros((VARYING_CAPACITY, 3), np.int64),
            np.zeros(STRATA_SLOTS, np.uint64),
        ),
        RayStack(
            np.empty((rays, 3)),
            np.empty((rays, 3)),
            np.empty((rays, 3)),
            np.empty(rays, np.int64),
            np.zeros(rays, np.int64),
            np.zeros(rays, np.int64),
            np.zeros(rays, np.int64),
            np.full(rays, -1, np.int64),
            np.zeros(rays, np.int64),
        ),
        np.zeros(1, np.int64) if cancel is None else cancel,
        np.zeros(REC_COUNT),
        np.zeros(ACC_COUNT),
        np.zeros((max(crypto_rays, 1), 3)),
        np.zeros((max(crypto_rays, 1), 2)),
        np.zeros(SHADER_STACK),
        np.zeros(LOBE_COUNT),
        np.zeros((2, corner_columns, CORNER_SLOTS)),
    )
