"""The passes in the kernels: what one camera ray records, and how a pixel's records become
its pass values (see `core.passes` for what each pass holds).

`trace_ray` fills a record (Workspace.record) per camera ray when any pass is asked for:
its first hit's point, normal, texture coordinates, ids and terms, and what its reflected
and refracted subtrees add. `render_tile` folds the records of a pixel's rays into
Workspace.accum (sums for the averaged passes, the nearest hit for depth, position and the
indices, the ids for Cryptomatte) and writes them after the pixel's RGBA. With no pass asked
for none of this runs: one test per camera ray.
"""

import math

from ..jit.decorators import kernel
from ..vocabulary import PASS_SLOT
from .options import OPTION_CRYPTO_LEVELS, OPTION_PROJECTION, PROJECTION_ORTHOGRAPHIC
from .vec import cross, dot, normalize, row, sub

# Slots of a camera ray's record (float64)
REC_HIT = 0  # 1 if it met a surface that is not a holdout
REC_POSITION = 1  # xyz of the first hit
REC_NORMAL = 4  # its shading normal, facing the ray
REC_UV = 7  # its texture coordinates u, v
REC_OBJECT_INDEX = 9
REC_MATERIAL_INDEX = 10
REC_OBJECT_ID = 11  # Cryptomatte ids of its object and material
REC_MATERIAL_ID = 12
REC_DIFFUSE_COLOR = 13  # kd (1 - transparency)
REC_LIT = 16  # the direct light falling on it (N.L-weighted) that its shadow rays let through
REC_UNSHADOWED = 19  # the same with no shadows
# Combined's terms, RGB each, in core.passes.TERMS order: a ray's colour goes to one of them
REC_ENVIRONMENT = 22
REC_AMBIENT = 25
REC_DIFFUSE = 28
REC_SPECULAR = 31
REC_REFLECTION = 34
REC_REFRACTION = 37
REC_EMISSION = 40
REC_COUNT = 43
TERM_COUNT = 7

# Slots of a pixel's accumulator (float64): sums over its rays, then its nearest hit
ACC_MIST = 0
ACC_NORMAL = 1
ACC_UV = 4  # u, v and the coverage
ACC_DIFFUSE_COLOR = 7
ACC_SHADOW = 10
ACC_TERMS = 13  # TERM_COUNT RGB sums, in REC_ENVIRONMENT.. order
ACC_DEPTH = 34  # of the nearest hit (inf: none yet)
ACC_POSITION = 35
ACC_OBJECT_INDEX = 38
ACC_MATERIAL_INDEX = 39
ACC_COUNT = 40

# Rows of Stacks.terms: the light falling on one shading point (N.L-weighted), through its
# shadows and without them (see shading.local_colour)
TERM_ROW_LIT, TERM_ROW_UNSHADOWED = 0, 1
TERM_ROWS = 2

BACKGROUND_DEPTH = 1e10

P_DEPTH = PASS_SLOT["depth"]
P_MIST = PASS_SLOT["mist"]
P_NORMAL = PASS_SLOT["normal"]
P_POSITION = PASS_SLOT["position"]
P_UV = PASS_SLOT["uv"]
P_OBJECT_INDEX = PASS_SLOT["object_index"]
P_MATERIAL_INDEX = PASS_SLOT["material_index"]
P_DIFFUSE_COLOR = PASS_SLOT["diffuse_color"]
P_SHADOW = PASS_SLOT["shadow"]
P_ENVIRONMENT = PASS_SLOT["environment"]
P_CRYPTO_OBJECT = PASS_SLOT["crypto_object"]
P_CRYPTO_MATERIAL = PASS_SLOT["crypto_material"]


@kernel
def add_to(record, slot, rgb):
    record[slot] += rgb[0]
    record[slot + 1] += rgb[1]
    record[slot + 2] += rgb[2]


@kernel
def _put(record, slot, xyz):
    record[slot], record[slot + 1], record[slot + 2] = xyz[0], xyz[1], xyz[2]


@kernel
def record_hit(record, surf, mats, shape, material, p, n, u, v, opacity, kd):
    """A camera ray's first hit (not a holdout): where, which, and its diffuse colour."""
    record[REC_HIT] = 1.0
    _put(record, REC_POSITION, p)
    _put(record, REC_NORMAL, n)
    record[REC_UV], record[REC_UV + 1] = u, v
    record[REC_OBJECT_INDEX] = surf.shape_pass_index[shape]
    record[REC_MATERIAL_INDEX] = mats.pass_index[material]
    record[REC_OBJECT_ID] = surf.shape_crypto[shape]
    record[REC_MATERIAL_ID] = mats.crypto[material]
    _put(record, REC_DIFFUSE_COLOR, (kd[0] * opacity, kd[1] * opacity, kd[2] * opacity))


@kernel
def record_lighting(record, terms, local, kd, ks, ambient, opacity, split):
    """The first hit's own colour `local`, split: ambient, direct diffuse (kd times the light
    falling through the shadows) and specular (what remains: the highlights, exactly
    what the colour holds beyond the other two, so the terms add up to it), each times the
    opacity as Combined takes them; and the light reaching it, with and without shadows.
    Without `split` (no diffuse, specular or shadow pass asked for) only ambient is known."""
    for a in range(3):
        ambient_part = kd[a] * ambient[a]
        record[REC_AMBIENT + a] += ambient_part * opacity
        if split:
            diffuse_part = kd[a] * terms[TERM_ROW_LIT, a]
            record[REC_DIFFUSE + a] += diffuse_part * opacity
            if ks[a] > 0.0:
                record[REC_SPECULAR + a] += (local[a] - ambient_part - diffuse_part) * opacity
            record[REC_LIT + a] = terms[TERM_ROW_LIT, a]
            record[REC_UNSHADOWED + a] = terms[TERM_ROW_UNSHADOWED, a]


@kernel
def view_axis(frame):
    """The camera's unit view direction (the forward row is off it under a lens shift)."""
    return normalize(cross(row(frame.camera, 3), row(frame.camera, 2)))


@kernel
def _mist(frame, distance):
    start, inverse_depth, power = frame.mist[0], frame.mist[1], frame.mist[2]
    ramp = min(1.0, max(0.0, (distance - start) * inverse_depth))
    if power == 1.0:
        return ramp
    if power == 2.0:
        return ramp * ramp
    return math.sqrt(ramp) if power == 0.5 else ramp**power


@kernel
def accumulate(acc, crypto_ids, record, sample, frame, axis):
    """Fold camera ray `sample`'s record into the pixel's sums and nearest hit."""
    for t in range(TERM_COUNT * 3):
        acc[ACC_TERMS + t] += record[REC_ENVIRONMENT + t]
    # One row per camera ray only when Cryptomatte is made (Workspace.crypto_ids)
    keep_ids = sample < crypto_ids.shape[0]
    if keep_ids:
        crypto_ids[sample, 0] = record[REC_HIT]
    if record[REC_HIT] == 0.0:
        acc[ACC_MIST] += 1.0
        for a in range(3):
            acc[ACC_SHADOW + a] += 1.0
        return
    if keep_ids:
        crypto_ids[sample, 1] = record[REC_OBJECT_ID]
        crypto_ids[sample, 2] = record[REC_MATERIAL_ID]
    p = (record[REC_POSITION], record[REC_POSITION + 1], record[REC_POSITION + 2])
    eye = row(frame.camera, 0)
    depth = dot(sub(p, eye), axis)
    if frame.options[OPTION_PROJECTION] == PROJECTION_ORTHOGRAPHIC:
        distance = depth
    else:
        offset = sub(p, eye)
        distance = math.sqrt(dot(offset, offset))
    acc[ACC_MIST] += _mist(frame, distance)
    for a in range(3):
        acc[ACC_NORMAL + a] += record[REC_NORMAL + a]
        acc[ACC_DIFFUSE_COLOR + a] += record[REC_DIFFUSE_COLOR + a]
        unshadowed = record[REC_UNSHADOWED + a]
        acc[ACC_SHADOW + a] += record[REC_LIT + a] / unshadowed if unshadowed > 0.0 else 1.0
    acc[ACC_UV] += record[REC_UV]
    acc[ACC_UV + 1] += record[REC_UV + 1]
    acc[ACC_UV + 2] += 1.0
    if depth < acc[ACC_DEPTH]:
        acc[ACC_DEPTH] = depth
        for a in range(3):
            acc[ACC_POSITION + a] = p[a]
        acc[ACC_OBJECT_INDEX] = record[REC_OBJECT_INDEX]
        acc[ACC_MATERIAL_INDEX] = record[REC_MATERIAL_INDEX]


@kernel
def clear(values, first_value):
    values[:] = 0.0
    values[0] = first_value


@kernel
def start_pixel(acc):
    acc[:] = 0.0
    acc[ACC_DEPTH] = math.inf


@kernel
def _write(out, j, i, offset, acc, first, count, scale):
    if offset >= 0:
        for c in range(count):
            out[j, i, 4 + offset + c] = acc[first + c] * scale


@kernel
def write_passes(out, j, i, frame, acc, crypto_ids, distinct, samples):
    """The pixel's passes after its RGBA, each where Frame.pass_offset says (or nowhere)."""
    offsets = frame.pass_offset
    mean = 1.0 / samples
    if offsets[P_DEPTH] >= 0:
        nearest = acc[ACC_DEPTH]
        out[j, i, 4 + offsets[P_DEPTH]] = nearest if nearest < math.inf else BACKGROUND_DEPTH
    _write(out, j, i, offsets[P_MIST], acc, ACC_MIST, 1, mean)
    _write(out, j, i, offsets[P_NORMAL], acc, ACC_NORMAL, 3, mean)
    _write(out, j, i, offsets[P_POSITION], acc, ACC_POSITION, 3, 1.0)
    _write(out, j, i, offsets[P_UV], acc, ACC_UV, 3, mean)
    _write(out, j, i, offsets[P_OBJECT_INDEX], acc, ACC_OBJECT_INDEX, 1, 1.0)
    _write(out, j, i, offsets[P_MATERIAL_INDEX], acc, ACC_MATERIAL_INDEX, 1, 1.0)
    _write(out, j, i, offsets[P_DIFFUSE_COLOR], acc, ACC_DIFFUSE_COLOR, 3, mean)
    _write(out, j, i, offsets[P_SHADOW], acc, ACC_SHADOW, 3, mean)
    for t in range(TERM_COUNT):
        _write(out, j, i, offsets[P_ENVIRONMENT + t], acc, ACC_TERMS + 3 * t, 3, mean)
    levels = frame.options[OPTION_CRYPTO_LEVELS]
    for k in range(2):
        offset = offsets[P_CRYPTO_OBJECT + k]
        if offset >= 0:
            _write_ranks(out, j, i, 4 + offset, crypto_ids, 1 + k, samples, levels, distinct)


@kernel
def _write_ranks(out, j, i, first, crypto_ids, column, samples, levels, distinct):
    """Cryptomatte: the pixel's distinct ids in crypto_ids[:, column] (of rays that met
    something) with the share of its rays each covers, the largest `levels` of them in
    decreasing coverage (ties: the smaller id first) as (id, coverage) pairs from channel
    `first`, zeros after. `distinct` is scratch for (id, count) rows."""
    found = 0
    for s in range(samples):
        if crypto_ids[s, 0] == 0.0:
            continue
        id_ = crypto_ids[s, column]
        k = 0
        while k < found and distinct[k, 0] != id_:
            k += 1
        if k == found:
            distinct[k, 0], distinct[k, 1] = id_, 0.0
            found += 1
        distinct[k, 1] += 1.0
    for c in range(4 * ((levels + 1) // 2)):
        out[j, i, first + c] = 0.0
    # Selection by hand, the largest first: a pixel has a handful of ids
    for rank in range(min(levels, found)):
        best = rank
        for k in range(rank + 1, found):
            more = distinct[k, 1] > distinct[best, 1]
            if more or (distinct[k, 1] == distinct[best, 1] and distinct[k, 0] < distinct[best, 0]):
                best = k
        id_, count = distinct[best, 0], distinct[best, 1]
        distinct[best, 0], distinct[best, 1] = distinct[rank, 0], distinct[rank, 1]
        distinct[rank, 0], distinct[rank, 1] = id_, count
        out[j, i, first + 2 * rank] = id_
        out[j, i, first + 2 * rank + 1] = count / samples
